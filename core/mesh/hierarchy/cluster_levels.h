#pragma once
// The meshes of the shadow hierarchy's nodes (core/mesh/hierarchy/mesh_clusters.h), after its tree:
// the inner nodes' simplified meshes and every node's coarser levels, built on all cores (each
// node's simplification on one thread, the results appended in node order, so the hierarchy is
// the same on any number of threads). Internal to build_mesh_clusters.
#include "core/mesh/hierarchy/mesh_clusters.h"

#include <vector>

namespace irad {

// Each inner node's mesh: its children's meshes joined and simplified to half (meshoptimizer,
// the region's border locked; simplify false: joined only), its error the larger of its
// children's plus the step's. Appended to out.indices after the original part.
void simplify_inner_nodes(const Scene& scene, MeshClusters& out, bool simplify, unsigned threads);

// Every node's coarser levels (at most max_levels), each simplifying its region's border too,
// each a `step`-th of the one before (2 or 4); whole[n]: node n is the root of one connected
// component, whose levels simplify the whole component, its open edges locked, a quarter at a
// time. leaf_levels false: leaves (other than such roots) keep none.
void add_coarser_levels(const Scene& scene, MeshClusters& out, int max_levels, int step,
                        const std::vector<bool>& whole, bool leaf_levels, unsigned threads);

} // namespace irad
