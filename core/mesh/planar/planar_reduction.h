#pragma once
// An exact reduction of the flat parts of a triangle mesh, for the shadow level of detail
// (core/mesh/hierarchy/mesh_clusters.h): a wall tessellated into 10^5 triangles becomes the few
// triangles its outline needs, before any error-driven simplification.
//
// Patches: triangles grown across shared edges from a seed (the largest octave of area first)
// while all three vertices lie within `epsilon` of the seed's plane and the triangle faces the
// same way (so the two faces of a zero-thickness wall never merge). Then edge collapses v -> u onto
// existing vertices (no vertex moves), of two kinds only:
//   - v inside one patch (a closed manifold fan, every edge shared by two triangles of the
//     patch) onto any neighbour u;
//   - v on a straight feature chain (a patch border or an open edge; v on exactly two of them)
//     onto one of its two neighbours along the chain. A chain is straight when every vertex on
//     it lies within `epsilon` of the line through its two ends.
// A collapse is made only when the link condition holds (the mesh stays manifold where it was)
// and every triangle it changes keeps facing its patch's way with a non-degenerate angle: the
// new fan then tiles the old one's projection onto the plane exactly. So the result covers the
// same surface, every point within 2 epsilon of the original (the plane's thickness) and the
// outline within epsilon (the chains), and stays watertight where the input was: every edge
// the collapses create is shared as the edge it replaces was. Curved parts (no two adjacent
// triangles coplanar) come out unchanged.
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

namespace irad {

struct PlanarReduction {
  std::vector<glm::uvec3> triangles; // the reduced mesh, same vertex indices, same winding
  std::size_t patches = 0;           // planar patches found
  std::size_t collapses = 0;         // vertices removed
};

// `triangles` index `positions` and share vertices where they meet (weld first). Triangles of
// exactly zero area cover nothing and are dropped. Deterministic. The vertices `locked` marks
// (empty: none) are never removed, so the edges between two of them stay as they are: a part
// of a mesh reduced with the vertices it shares with the rest locked still fits the rest.
PlanarReduction reduce_planar(const std::vector<glm::vec3>& positions,
                              const std::vector<glm::uvec3>& triangles, float epsilon,
                              const std::vector<bool>& locked = {});

} // namespace irad
