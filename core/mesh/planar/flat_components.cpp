#include "core/mesh/planar/flat_components.h"

#include "core/mesh/planar/planar_chunks.h"
#include "core/mesh/planar/vertex_fans.h"

#include <algorithm>
#include <glm/glm.hpp>
#include <numeric>

namespace irad {

std::vector<std::uint32_t> triangle_components(const std::vector<glm::uvec3>& triangles,
                                               std::size_t vertices) {
  std::vector<std::uint32_t> parent(vertices);
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const glm::uvec3& t : triangles) {
    const std::uint32_t a = find(t.x);
    parent[find(t.y)] = a;
    parent[find(t.z)] = a;
  }
  std::vector<std::uint32_t> component(triangles.size());
  for (std::size_t k = 0; k < triangles.size(); ++k) component[k] = find(triangles[k].x);
  return component;
}

namespace {

// Up to kFlatSamples triangles of each component, evenly spaced in order.
std::vector<std::uint32_t> samples(const std::vector<std::uint32_t>& component,
                                   std::size_t vertices) {
  std::vector<std::uint32_t> count(vertices, 0), seen(vertices, 0);
  for (std::uint32_t c : component) ++count[c];
  std::vector<std::uint32_t> out;
  for (std::uint32_t k = 0; k < component.size(); ++k) {
    const std::uint32_t c = component[k];
    const std::uint32_t step = std::max<std::uint32_t>(1, count[c] / kFlatSamples);
    if (seen[c]++ % step == 0) out.push_back(k);
  }
  return out;
}

// The fans of the vertices of the triangles `around` (other vertices' fans left empty).
VertexFans fans_around(const std::vector<glm::uvec3>& triangles, std::size_t vertices,
                       const std::vector<std::uint32_t>& around) {
  std::vector<bool> wanted(vertices, false);
  for (std::uint32_t k : around)
    for (int c = 0; c < 3; ++c) wanted[triangles[k][c]] = true;
  return VertexFans(
      triangles, vertices, [](std::uint32_t) { return true; },
      [&](std::uint32_t v) { return static_cast<bool>(wanted[v]); });
}

// Whether some vertex of triangle k has its whole fan (every triangle around it) within epsilon
// of k's plane, facing its way: a vertex the reduction could remove from inside a patch. (Two
// coplanar triangles of a quad are not enough: on a UV sphere every quad is planar and nothing
// can be removed.)
bool has_planar_vertex(const std::vector<glm::vec3>& positions,
                       const std::vector<glm::uvec3>& triangles, const VertexFans& fans,
                       std::uint32_t k, float epsilon) {
  const glm::uvec3 t = triangles[k];
  const auto p = [&](std::uint32_t v) { return glm::dvec3(positions[v]); };
  const glm::dvec3 cross = glm::cross(p(t.y) - p(t.x), p(t.z) - p(t.x));
  const double area = glm::length(cross);
  if (!(area > 0.0)) return false;
  const glm::dvec3 n = cross / area;
  const double d = glm::dot(n, p(t.x));
  const auto in_plane = [&](std::uint32_t s) {
    const glm::uvec3 o = triangles[s];
    if (!(glm::dot(glm::cross(p(o.y) - p(o.x), p(o.z) - p(o.x)), n) > 0.0)) return false;
    for (int c = 0; c < 3; ++c)
      if (std::abs(glm::dot(n, p(o[c])) - d) > epsilon) return false;
    return true;
  };
  for (int c = 0; c < 3; ++c) {
    bool planar = true;
    for (std::uint32_t i = fans.first[t[c]]; i < fans.first[t[c] + 1] && planar; ++i)
      planar = in_plane(fans.list[i]);
    if (planar) return true;
  }
  return false;
}

} // namespace

PlanarReduction reduce_flat_components(const std::vector<glm::vec3>& positions,
                                       std::vector<glm::uvec3> triangles, float epsilon) {
  const std::vector<std::uint32_t> component = triangle_components(triangles, positions.size());
  const std::vector<std::uint32_t> sampled = samples(component, positions.size());
  const VertexFans fans = fans_around(triangles, positions.size(), sampled);
  // Per component root: its samples, and of them those with a planar vertex.
  std::vector<std::uint32_t> tried(positions.size(), 0), found(positions.size(), 0);
  for (std::uint32_t k : sampled) {
    ++tried[component[k]];
    if (has_planar_vertex(positions, triangles, fans, k, epsilon)) ++found[component[k]];
  }
  std::vector<bool> flat(positions.size(), false);
  for (std::size_t c = 0; c < flat.size(); ++c)
    flat[c] = tried[c] > 0 && found[c] * kFlatShare >= tried[c];
  std::size_t flat_triangles = 0;
  for (std::uint32_t c : component) flat_triangles += flat[c] ? 1 : 0;
  if (flat_triangles == triangles.size())
    return reduce_planar_chunked(positions, triangles, epsilon);
  PlanarReduction out;
  if (flat_triangles == 0) { // nothing to reduce: the triangles as they came, no copy
    out.triangles = std::move(triangles);
    return out;
  }
  std::vector<glm::uvec3> reducible, kept;
  reducible.reserve(flat_triangles);
  kept.reserve(triangles.size() - flat_triangles);
  for (std::size_t k = 0; k < triangles.size(); ++k)
    (flat[component[k]] ? reducible : kept).push_back(triangles[k]);
  triangles = {}; // split: not held through the reduction
  out = reduce_planar_chunked(positions, reducible, epsilon);
  reducible = {};
  out.triangles.insert(out.triangles.end(), kept.begin(), kept.end());
  return out;
}

} // namespace irad
