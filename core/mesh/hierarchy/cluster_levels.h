#pragma once
// The meshes of the shadow hierarchy's nodes (core/mesh/hierarchy/mesh_clusters.h), after its tree:
// the inner nodes' simplified meshes and every node's coarser levels, built on all cores (each
// node's simplification on one thread, the results appended in node order, so the hierarchy is
// the same on any number of threads; with deferred levels, which nodes have theirs built with it
// is not, their levels are). Internal to build_mesh_clusters.
#include "core/mesh/hierarchy/mesh_clusters.h"

#include <cstdint>
#include <vector>

namespace irad {

// Each inner node's mesh: its children's meshes joined and simplified to half (meshoptimizer,
// the region's border locked; simplify false: joined only), its error the larger of its
// children's plus the step's. Appended to out.indices after the original part.
void simplify_inner_nodes(const Scene& scene, MeshClusters& out, bool simplify, unsigned threads);

// Every node's coarser levels (at most max_levels), each simplifying its region's border too,
// each a `step`-th of the one before (2 or 4); whole[n]: node n is the root of one connected
// component, whose levels simplify the whole component, its open edges locked, a quarter at a
// time. leaf_levels false: leaves (other than such roots) keep none. defer: such roots get theirs
// first, and the other nodes, from the top down, only while a root's task still runs (on cores
// that would otherwise wait for it: which ones depends on the timing); the rest are left pending
// (ClusterNode::levels_pending), and out.deferred_max_levels and deferred_step keep what
// add_deferred_levels builds them with.
void add_coarser_levels(const Scene& scene, MeshClusters& out, int max_levels, int step,
                        const std::vector<bool>& whole, bool leaf_levels, bool defer,
                        unsigned threads);

// The levels of those of `nodes` that are pending, the very levels add_coarser_levels would
// have built (their meshes read from c.indices or c.stored_indices, each node on one of
// `threads` threads): appended to c.levels, their indices to c.late_indices from the next
// multiple of kLateAlign, in node order. Throws Error where a stored index cannot be read back
// (StoredIndices::copy_range) or the index space would pass 2^32.
void add_deferred_levels(const Scene& scene, MeshClusters& c, std::vector<std::int32_t> nodes,
                         unsigned threads);

} // namespace irad
