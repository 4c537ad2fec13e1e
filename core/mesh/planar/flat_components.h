#pragma once
// reduce_planar (core/mesh/planar/planar_reduction.h) only where it can find something. Its patch
// growth visits every triangle in order of area, a random walk through memory that costs more
// than the rest of the shadow hierarchy's build on a large curved mesh, where it finds little
// (a 10M-triangle terrain: 5 % of its triangles in 23 s of the build's 54). So each connected
// component (triangles joined through shared vertices) is sampled first: up to kFlatSamples of its
// triangles, evenly spaced, each asked whether one of its vertices has its whole fan within epsilon
// of the triangle's plane and facing its way (a vertex a patch could lose). A component where at
// least 1/kFlatShare of the samples have one is reduced; the others come out unchanged. Sampling
// can miss the rare flat spots of a curved component: they then keep their triangles, which costs
// shadow faces triangles, never correctness.
#include "core/mesh/planar/planar_reduction.h"

#include <cstddef>

namespace irad {

inline constexpr std::size_t kFlatSamples = 512;
// A component is reduced when at least 1/kFlatShare of its samples have a planar vertex. The
// 10M-triangle terrain of scripts/make_large_glb.py (--quads 2236) has 37 of 513: reduced, it
// loses 5 % of its triangles in 23 s; the 2.1M-triangle sphere of scripts/make_sphere_box.py,
// finer than the tolerance, has 505 and loses 16 % in 2.1 s.
inline constexpr std::uint32_t kFlatShare = 4;

// Each triangle's connected component through shared vertices, named by a vertex of it (the
// same vertex for every triangle of one component).
std::vector<std::uint32_t> triangle_components(const std::vector<glm::uvec3>& triangles,
                                               std::size_t vertices);

// reduce_planar over the components that sampling finds flat parts in (on all cores, in spatial
// chunks where they hold more than kPlanarChunkTriangles: core/mesh/planar/planar_chunks.h); their
// reduced triangles first, then the other components' triangles unchanged, in their order.
// patches and collapses are the reduction's. Every component flat:
// reduce_planar_chunked(positions, triangles, epsilon); none: `triangles` themselves, moved
// (taken by value: a big mesh with nothing flat, such as a terrain, comes back without a copy,
// 240 MB fewer in the 10M-triangle terrain's build).
PlanarReduction reduce_flat_components(const std::vector<glm::vec3>& positions,
                                       std::vector<glm::uvec3> triangles, float epsilon);

} // namespace irad
