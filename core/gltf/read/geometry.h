#pragma once
// Internal to the glTF loader: triangle primitives to world-space triangles.
#include "core/animation/animation.h"
#include "core/gltf/context.h"
#include "core/scene/scene.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace irad::gltf {

// World-space triangles gathered from primitives, before clean-up.
struct Soup {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals; // unit, or 0 where unknown (filled by finish_geometry)
  // The optional sets stay empty until a primitive has them (then (0, 0), (0, 0), 1 for the
  // vertices of the primitives without).
  std::vector<glm::vec2> uvs;    // uv slot 0
  std::vector<glm::vec2> uvs1;   // uv slot 1
  std::vector<glm::vec4> colors; // COLOR_0, 1 for primitives without it
  // Placed tangents (xyz unit, w = +-1) of the primitives whose material has a normal map, 0 for
  // the vertices of the others (filled by finish_geometry).
  std::vector<glm::vec4> tangents;
  bool has_uvs = false; // some primitive had the set of slot 0
  bool has_uvs1 = false;
  bool has_colors = false;
  bool has_tangents = false;
  std::vector<glm::uvec3> triangles;
  std::vector<std::uint32_t> triangle_material;
  std::vector<std::uint32_t> vertex_node; // glTF node per vertex, kept only for animated files
  // Skinned or morphed primitives of an animated file, kept so that the animation can pose them
  // (core/animation/animation.h): part.vertices are soup indices until finish_geometry maps them;
  // the glTF nodes of the mesh and of the skin's joints are mapped by read_animation.
  struct Deform {
    std::size_t gltf_node;
    std::vector<std::size_t> gltf_joints;
    Animation::DeformedPart part;
  };
  std::vector<Deform> deforms;
  bool record_deforms = false;
  std::size_t non_finite_dropped = 0; // triangles with a NaN or Inf (placed) vertex position
  std::string non_finite_where;       // the primitive of the first of them
  // What the whole scene appends (add_size_hint), so that each array is allocated once instead
  // of growing by half at the first primitive that does not fit.
  std::size_t vertex_hint = 0, triangle_hint = 0;
};

// The TEXCOORD sets a material's textures read, in the scene's two uv slots (Scene::uvs and
// Scene::uvs1); -1: the slot is not used. core/gltf/read/materials.h assigns them.
// tangent_slot: the uv slot (0 or 1) of the material's normal map, whose texture coordinates
// MikkTSpace tangents follow; -1: the material has no normal map and its primitives no tangents.
struct UvSets {
  int slot0 = -1;
  int slot1 = -1;
  int tangent_slot = -1;
};

// Where a primitive's vertices go: by its node's world matrix, after the morph targets' weighted
// displacements (glTF 3.7.2.2), or, for a skinned mesh, by the weighted joint matrices
// (joint world x inverse bind matrix; the node's own transform is ignored, glTF 3.7.3).
struct SkinPose;
struct PrimitivePose {
  std::size_t node = 0; // the glTF node drawing the mesh
  glm::dmat4 world{1.0};
  std::vector<double> morph_weights; // empty: no morphing
  const SkinPose* skin = nullptr;    // non-null: skinned
};

// Appends meshes[mesh].primitives[primitive] placed by `pose`, all its triangles getting scene
// material `material`, with the uv sets `uv`. Modes TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN are
// converted to triangle lists; point and line primitives are skipped with one warning per file.
// Positions are p' = world p; normals n' = normalize(N n) with N the inverse transpose of the
// upper 3x3 block, taken as cofactor(A) sign(det A) = |det A| A^-T so that singular blocks need no
// inverse. When det A < 0 the winding is reversed, so cross(p1 - p0, p2 - p0) keeps pointing to
// the side N n points to (cross(Aa, Ab) = cofactor(A) cross(a, b)). Without NORMAL the primitive
// is de-indexed (three vertices per triangle) and its normals are left for finish_geometry.
// Tangents, for a primitive with uv.tangent_slot >= 0 only: its TANGENT (VEC4) where it has one,
// else MikkTSpace tangents (core/mesh/tangents.h) of its positions, normals (without NORMAL, the
// de-indexed triangles' own normals) and the slot's texture coordinates ((0, 0) without them),
// computed in the file's frame before morphing and skinning; a vertex whose corners get
// different tangents is copied. Placed as t' = normalize(A t.xyz), w' = w sign(det A) (skinned:
// the blended joint matrix is A), morph targets' TANGENT displacements added first.
// Triangles with a vertex whose placed position is NaN or Inf are dropped (counted in the soup;
// finish_geometry warns once). Fails on missing POSITION, mismatched attribute counts, index
// values >= the vertex count, and triangles or vertices beyond ctx.limits (3 vertices per allowed
// triangle), before allocating them.
// A primitive without POSITION is skipped with a warning (glTF allows it); a
// KHR_draco_mesh_compression primitive is decoded first (core/gltf/decode/codecs.h).
void append_primitive(const Context& ctx, std::size_t mesh, std::size_t primitive,
                      const PrimitivePose& pose, std::uint32_t material, UvSets uv, Soup& soup);

// Adds the vertices and triangles of meshes[mesh]'s primitives to soup's hints, as their
// accessors' counts give them (the JSON alone: nothing is read or checked, an index out of range
// adds nothing; append_primitive checks the real counts), capped by ctx.limits.
void add_size_hint(const Context& ctx, std::uint64_t mesh, Soup& soup);

// Moves the soup into scene (and soup.vertex_node, compacted like the vertices, into
// *vertex_node when given) (positions, normals, uvs, tangents, triangles, triangle_material,
// bounds):
// warns once when triangles with non-finite positions were dropped,
// drops triangles with a repeated vertex or with area <= 1e-12 diagonal^2 (one warning with the
// count), gives each vertex without a usable normal the geometric normal of the first triangle
// that uses it, gives each vertex without a usable tangent (when soup.has_tangents) a unit one
// orthogonal to its normal with w = 1, and drops vertices no triangle uses. uvs stay empty
// unless soup.has_uvs, tangents unless soup.has_tangents.
// soup.deforms' vertices are mapped to scene vertices (those of dropped vertices removed) into
// *deforms when given.
void finish_geometry(const Context& ctx, Soup soup, Scene& scene,
                     std::vector<std::uint32_t>* vertex_node = nullptr,
                     std::vector<Soup::Deform>* deforms = nullptr);

} // namespace irad::gltf
