#pragma once
// reduce_planar (core/mesh/planar/planar_reduction.h) on all cores. Its patch growth and collapses
// are serial walks through the mesh; on a finely tessellated curved surface, flat within epsilon
// over a few rings of triangles, they cost most of the shadow hierarchy's build (the 10M-triangle
// sphere of scripts/make_sphere_box.py: 7.2 s of a 17.7 s cold render on one thread).
//
// So a large mesh is split into spatial chunks of at most `chunk` triangles: median splits of
// the triangles' centroids along the longest axis of their bounds, level by level, the ranges of
// a level split on all cores. Each chunk is reduced on its own, over its own vertices, with the
// vertices it shares with another chunk locked: the edges between two locked vertices stay as
// they are, so the chunks still fit each other and the result stays watertight where the input
// was. A patch ends at a chunk's border, which costs the result a few triangles along the
// borders. The chunks depend on the triangles alone (not on the threads): the same result on
// any number of threads. A mesh of at most `chunk` triangles is reduce_planar's.
#include "core/mesh/planar/planar_reduction.h"

#include <cstddef>

namespace irad {

inline constexpr std::size_t kPlanarChunkTriangles = std::size_t{1} << 17;

// The chunks: lists of triangle indices, each ascending (the mesh's own order, as reduce_planar
// seeds its patches), in a fixed order.
std::vector<std::vector<std::uint32_t>> spatial_chunks(const std::vector<glm::vec3>& positions,
                                                       const std::vector<glm::uvec3>& triangles,
                                                       std::size_t chunk, unsigned threads = 0);

// reduce_planar's contract, chunk by chunk (above); the chunks' triangles in chunk order,
// patches and collapses summed. threads: 0 all cores.
PlanarReduction reduce_planar_chunked(const std::vector<glm::vec3>& positions,
                                      const std::vector<glm::uvec3>& triangles, float epsilon,
                                      std::size_t chunk = kPlanarChunkTriangles,
                                      unsigned threads = 0);

} // namespace irad
