// finish_geometry (core/gltf/read/geometry.h): the soup's clean-up into the scene.
#include "core/gltf/read/geometry.h"

#include "core/mesh/tangents.h"
#include "core/util/parallel_rows.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace irad::gltf {

namespace {

// (p1 - p0) x (p2 - p0) in double precision: |c| = 2 area, direction = front face.
glm::dvec3 edge_cross(const Soup& s, const glm::uvec3& t) {
  const glm::dvec3 p0(s.positions[t.x]);
  return glm::cross(glm::dvec3(s.positions[t.y]) - p0, glm::dvec3(s.positions[t.z]) - p0);
}

// The bounds of the triangles' vertices, chunks on all cores merged in order.
Bounds triangle_bounds(const std::vector<glm::vec3>& positions,
                       const std::vector<glm::uvec3>& triangles) {
  std::vector<Bounds> parts((triangles.size() + kParallelChunk - 1) / kParallelChunk);
  parallel_chunks(triangles.size(), [&](std::size_t first, std::size_t end) {
    Bounds& b = parts[first / kParallelChunk];
    for (std::size_t k = first; k < end; ++k) {
      const glm::uvec3& t = triangles[k];
      b.extend(positions[t.x]);
      b.extend(positions[t.y]);
      b.extend(positions[t.z]);
    }
  });
  Bounds b;
  for (const Bounds& part : parts) b.extend(part);
  return b;
}

// Keeps the non-degenerate triangles (tested on all cores, kept in order); returns how many
// were dropped.
std::size_t drop_degenerate(Soup& s) {
  const double diagonal = triangle_bounds(s.positions, s.triangles).diagonal();
  const double min_area = 1e-12 * diagonal * diagonal;
  std::vector<char> keep(s.triangles.size());
  parallel_chunks(keep.size(), [&](std::size_t first, std::size_t end) {
    for (std::size_t i = first; i < end; ++i) {
      const glm::uvec3 t = s.triangles[i];
      const bool repeated = t.x == t.y || t.y == t.z || t.z == t.x;
      keep[i] = !repeated && 0.5 * glm::length(edge_cross(s, t)) > min_area;
    }
  });
  if (std::find(keep.begin(), keep.end(), 0) == keep.end()) return 0;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    if (!keep[i]) continue;
    s.triangles[kept] = s.triangles[i];
    s.triangle_material[kept++] = s.triangle_material[i];
  }
  const std::size_t dropped = s.triangles.size() - kept;
  s.triangles.resize(kept);
  s.triangle_material.resize(kept);
  return dropped;
}

// Vertices without a usable normal take the geometric normal of the first triangle using them
// (nothing to do, and no pass over the triangles, where every vertex has one).
void fill_normals(Soup& s) {
  if (std::find(s.normals.begin(), s.normals.end(), glm::vec3(0.0f)) == s.normals.end()) return;
  for (const glm::uvec3& t : s.triangles) {
    const glm::vec3 n(glm::normalize(edge_cross(s, t)));
    for (std::uint32_t v : {t.x, t.y, t.z}) {
      if (s.normals[v] == glm::vec3(0.0f)) s.normals[v] = n;
    }
  }
}

// Vertices without a usable tangent (0: from a primitive without a normal map, or placed to
// nothing) take a unit one orthogonal to their normal, w = 1.
void fill_tangents(Soup& s) {
  parallel_chunks(s.tangents.size(), [&](std::size_t first, std::size_t end) {
    for (std::size_t v = first; v < end; ++v)
      if (glm::vec3(s.tangents[v]) == glm::vec3(0.0f))
        s.tangents[v] = glm::vec4(any_tangent(s.normals[v]), 1.0f);
  });
}

// Removes vertices no triangle uses, keeping the order of the others.
// Keeps the entries of a deformed part whose vertex survived compaction, renumbered. A flat part
// loses whole triangles (triples) only, so its triples stay aligned.
void remap_deform(const std::vector<std::uint32_t>& remap, const std::vector<char>& used,
                  Animation::DeformedPart& p) {
  std::size_t kept = 0;
  for (std::size_t k = 0; k < p.vertices.size(); ++k) {
    if (!used[p.vertices[k]]) continue;
    p.vertices[kept] = remap[p.vertices[k]];
    p.positions[kept] = p.positions[k];
    if (!p.normals.empty()) p.normals[kept] = p.normals[k];
    if (!p.tangents.empty()) p.tangents[kept] = p.tangents[k];
    for (auto& t : p.position_targets) t[kept] = t[k];
    for (auto& t : p.normal_targets) t[kept] = t[k];
    for (auto& t : p.tangent_targets) t[kept] = t[k];
    if (!p.vertex_joints.empty()) {
      p.vertex_joints[kept] = p.vertex_joints[k];
      p.vertex_weights[kept] = p.vertex_weights[k];
    }
    ++kept;
  }
  p.vertices.resize(kept);
  p.positions.resize(kept);
  if (!p.normals.empty()) p.normals.resize(kept);
  if (!p.tangents.empty()) p.tangents.resize(kept);
  for (auto& t : p.position_targets) t.resize(kept);
  for (auto& t : p.normal_targets) t.resize(kept);
  for (auto& t : p.tangent_targets) t.resize(kept);
  if (!p.vertex_joints.empty()) {
    p.vertex_joints.resize(kept);
    p.vertex_weights.resize(kept);
  }
}

void compact(Soup& s) {
  std::vector<std::uint32_t> remap(s.positions.size(), 0);
  for (const glm::uvec3& t : s.triangles) remap[t.x] = remap[t.y] = remap[t.z] = 1;
  if (std::find(remap.begin(), remap.end(), 0u) == remap.end()) return; // every vertex used
  const std::vector<char> used(remap.begin(), remap.end());
  std::uint32_t next = 0;
  for (std::size_t v = 0; v < s.positions.size(); ++v) {
    if (remap[v] == 0) continue;
    remap[v] = next;
    s.positions[next] = s.positions[v];
    s.normals[next] = s.normals[v];
    if (!s.vertex_node.empty()) s.vertex_node[next] = s.vertex_node[v];
    if (!s.uvs1.empty()) s.uvs1[next] = s.uvs1[v];
    if (!s.colors.empty()) s.colors[next] = s.colors[v];
    if (!s.uvs.empty()) s.uvs[next] = s.uvs[v];
    if (!s.tangents.empty()) s.tangents[next] = s.tangents[v];
    ++next;
  }
  s.positions.resize(next);
  s.normals.resize(next);
  if (!s.uvs.empty()) s.uvs.resize(next);
  if (!s.uvs1.empty()) s.uvs1.resize(next);
  if (!s.colors.empty()) s.colors.resize(next);
  if (!s.tangents.empty()) s.tangents.resize(next);
  if (!s.vertex_node.empty()) s.vertex_node.resize(next);
  for (glm::uvec3& t : s.triangles) t = {remap[t.x], remap[t.y], remap[t.z]};
  for (Soup::Deform& d : s.deforms) remap_deform(remap, used, d.part);
}

} // namespace

void finish_geometry(const Context& ctx, Soup soup, Scene& scene,
                     std::vector<std::uint32_t>* vertex_node, std::vector<Soup::Deform>* deforms) {
  if (soup.non_finite_dropped > 0) {
    ctx.warn(std::to_string(soup.non_finite_dropped) +
             " triangle(s) with a NaN or Inf vertex position dropped (the first in " +
             soup.non_finite_where + ")");
  }
  if (const std::size_t dropped = drop_degenerate(soup); dropped > 0) {
    ctx.warn(std::to_string(dropped) + " degenerate (zero-area) triangles dropped");
  }
  fill_normals(soup);
  fill_tangents(soup);
  compact(soup);
  scene.bounds = triangle_bounds(soup.positions, soup.triangles);
  scene.positions = std::move(soup.positions);
  // Room for one more: the ray tracer then reads the positions in place, with 16-byte loads that
  // reach past the last one (walk/rays/ray_scene.h), instead of copying them.
  scene.positions.reserve(scene.positions.size() + 1);
  scene.normals = std::move(soup.normals);
  if (soup.has_uvs) scene.uvs = std::move(soup.uvs);
  if (soup.has_uvs1) scene.uvs1 = std::move(soup.uvs1);
  if (soup.has_colors) scene.colors = std::move(soup.colors);
  if (soup.has_tangents) scene.tangents = std::move(soup.tangents);
  scene.triangles = std::move(soup.triangles);
  scene.triangle_material = std::move(soup.triangle_material);
  if (vertex_node) *vertex_node = std::move(soup.vertex_node);
  if (deforms) *deforms = std::move(soup.deforms);
}

} // namespace irad::gltf
