#pragma once
// MikkTSpace tangent frames for normal maps (glTF 2.0: "When tangents are not specified, client
// implementations SHOULD calculate tangents using default MikkTSpace algorithms"): the algorithm
// of M. Mikkelsen, "Simulation of Wrinkled Surfaces Revisited" (2008), as the reference
// mikktspace.c (genTangSpaceDefault, the one Blender and the glTF exporters run) computes it.
//
// Per triangle with uv differences (u1 - u0, v1 - v0) = (s1, t1), (u2 - u0, v2 - v0) = (s2, t2)
// (v growing up the image, the reference's convention) and edges e1 = p1 - p0, e2 = p2 - p0:
//   dp/du ~ t2 e1 - t1 e2,  dp/dv ~ -s2 e1 + s1 e2,  orientation sign = sign(s1 t2 - t1 s2),
// the derivatives taken to unit length times the orientation sign. A corner's tangent is the sum
// over the triangles of its group of their dp/du made orthogonal to the corner's normal and
// normalised, each weighted by the triangle's angle at the corner (measured in the normal's
// tangent plane; not by area), then normalised; w is the group's orientation sign. A group is the
// fan of triangles around one vertex, connected through shared edges (run in opposite directions
// by the two triangles), with one orientation sign: vertices count as the same where position,
// normal and uv are equal (welded), and a fan is cut where the sign changes, so corners of one
// vertex on two sides of a uv mirror get two frames. Within a group, a corner leaves out the
// triangles whose projected dp/du or dp/dv is exactly opposite to its own triangle's. A triangle
// whose uv area or derivatives vanish joins whichever group reaches it first, taking its sign,
// and adds no weight. A triangle with two equal corner positions takes, per corner, the frame of
// the first good corner of the same welded vertex. Corners that no group reaches get a unit
// vector orthogonal to their normal and w = +1.
//
// Conventions: uvs as glTF stores them (v grows down the image). w = +-1 with bitangent =
// w cross(normal, tangent) pointing up the image (toward -v), as glTF's TANGENT and normal
// textures define it: for u along +x and v along -y on a +z-facing quad, tangent +x and w = +1.
// This is the reference run on (u, 1 - v), Blender's uv convention, which is what the exporters
// that write MikkTSpace tangents into glTF compute.
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace irad {

// Tangents of an indexed triangle mesh, per corner: result[3 t + c] for corner c of triangle t
// (xyz unit and orthogonal to the corner's normalised normal, w = +-1). positions, normals and
// uvs are per vertex (equal sizes); normals need not be unit (a zero normal projects nothing).
// Time O(V log V + T log T) for V vertices and T triangles, plus the square of the triangles
// around a vertex where two of their tangents there point in exactly opposite directions
// (the reference's sub-groups). Throws std::invalid_argument on mismatched sizes or an index
// out of range.
std::vector<glm::vec4> mikktspace_tangents(const std::vector<glm::vec3>& positions,
                                           const std::vector<glm::vec3>& normals,
                                           const std::vector<glm::vec2>& uvs,
                                           const std::vector<glm::uvec3>& triangles);

// A mesh re-indexed so that each vertex has one tangent: where the corners of a vertex carry
// different tangents (MikkTSpace gives two frames on the two sides of a uv mirror or a fan cut),
// each further tangent gets a copy of the vertex. Vertices keep their indices (source[v] = v for
// every input vertex v); copies follow them.
struct TangentVertices {
  std::vector<std::uint32_t> source; // per vertex of the result: the input vertex it copies
  std::vector<glm::vec4> tangents;   // per vertex of the result; 0 where no triangle uses it
  std::vector<glm::uvec3> triangles; // the input triangles, re-indexed
};

// Splits the vertices of `triangles` (indices < vertex_count) by the per-corner tangents
// (corner_tangents[3 t + c], as mikktspace_tangents gives them): a vertex is copied once per
// distinct tangent (exact equality) beyond the first that its corners carry, in corner order.
// Throws std::invalid_argument on mismatched sizes or an index out of range.
TangentVertices split_by_tangent(std::size_t vertex_count, const std::vector<glm::uvec3>& triangles,
                                 const std::vector<glm::vec4>& corner_tangents);

// A unit vector orthogonal to the unit (or zero) normal n: the x axis made orthogonal to n, or
// the y axis where n lies within 26 degrees of x. The tangent of corners without a frame.
glm::vec3 any_tangent(const glm::vec3& n);

// The vertices of one mesh for a normal map: split_by_tangent of mikktspace_tangents. Empty
// `normals` means flat shading: every corner becomes a vertex of its own (source: the corner's
// vertex; triangle t gets vertices 3t, 3t + 1, 3t + 2) with its triangle's unit normal
// (p1 - p0) x (p2 - p0). Empty `uvs` means (0, 0) everywhere, so that every corner gets
// any_tangent and w = 1. Throws like mikktspace_tangents.
TangentVertices tangent_vertices(const std::vector<glm::vec3>& positions,
                                 const std::vector<glm::vec3>& normals,
                                 const std::vector<glm::vec2>& uvs,
                                 const std::vector<glm::uvec3>& triangles);

} // namespace irad
