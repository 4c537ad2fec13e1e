#include "core/gltf/geometry.h"

#include "core/gltf/accessors.h"

#include <cmath>
#include <limits>
#include <numeric>

namespace irad::gltf {

namespace {

// A primitive's vertex attributes in its mesh's frame.
struct Attributes {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals; // empty without NORMAL
  std::vector<glm::vec2> uvs;     // empty without TEXCOORD_0
};

int attribute(const tinygltf::Primitive& p, const char* name) {
  const auto it = p.attributes.find(name);
  return it == p.attributes.end() ? -1 : it->second;
}

Attributes read_attributes(const Context& ctx, const tinygltf::Primitive& p,
                           const std::string& where) {
  Attributes a;
  const int position = attribute(p, "POSITION");
  if (position < 0) ctx.fail(where, "has no POSITION attribute");
  a.positions = read_vec3(ctx, position, where + ".attributes.POSITION");
  const std::size_t n = a.positions.size();
  if (const int normal = attribute(p, "NORMAL"); normal >= 0) {
    a.normals = read_vec3(ctx, normal, where + ".attributes.NORMAL");
    if (a.normals.size() != n) ctx.fail(where, "NORMAL and POSITION counts differ");
  }
  if (const int uv = attribute(p, "TEXCOORD_0"); uv >= 0) {
    a.uvs = read_texcoords(ctx, uv, where + ".attributes.TEXCOORD_0");
    if (a.uvs.size() != n) ctx.fail(where, "TEXCOORD_0 and POSITION counts differ");
  }
  return a;
}

// Vertex indices of the primitive (0, 1, ..., n - 1 when it has none), each checked < n.
std::vector<std::uint32_t> read_vertex_indices(const Context& ctx, const tinygltf::Primitive& p,
                                               std::size_t n, const std::string& where) {
  if (p.indices < 0) {
    if (n > std::numeric_limits<std::uint32_t>::max()) ctx.fail(where, "too many vertices");
    std::vector<std::uint32_t> indices(n);
    std::iota(indices.begin(), indices.end(), std::uint32_t(0));
    return indices;
  }
  std::vector<std::uint32_t> indices = read_indices(ctx, p.indices, where + ".indices");
  for (std::uint32_t i : indices) {
    if (i >= n) {
      ctx.fail(where + ".indices", "index value " + std::to_string(i) + " out of range (" +
                                       std::to_string(n) + " vertices)");
    }
  }
  return indices;
}

// Triangle list from the index sequence of a TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN primitive
// (strip triangle k: (k, k+1, k+2), odd k (k+1, k, k+2); fan triangle k: (0, k+1, k+2)).
std::vector<glm::uvec3> assemble(const Context& ctx, int mode,
                                 const std::vector<std::uint32_t>& idx, const std::string& where) {
  std::vector<glm::uvec3> out;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (idx.size() % 3 != 0) ctx.fail(where, "TRIANGLES index count is not a multiple of 3");
    for (std::size_t k = 0; k + 2 < idx.size(); k += 3)
      out.emplace_back(idx[k], idx[k + 1], idx[k + 2]);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    for (std::size_t k = 0; k + 2 < idx.size(); ++k) {
      if (k % 2 == 0)
        out.emplace_back(idx[k], idx[k + 1], idx[k + 2]);
      else
        out.emplace_back(idx[k + 1], idx[k], idx[k + 2]);
    }
  } else {
    for (std::size_t k = 1; k + 1 < idx.size(); ++k) out.emplace_back(idx[0], idx[k], idx[k + 1]);
  }
  return out;
}

// The placement of a primitive: points by A p + t, normals by cofactor(A) sign(det A).
struct Placement {
  glm::dmat4 world;
  glm::dmat3 normal_matrix;
  bool flip; // det A < 0: reverse the winding
};

Placement placement(const glm::dmat4& world) {
  const glm::dmat3 a(world);
  const double det = glm::determinant(a);
  const double sign = det < 0.0 ? -1.0 : 1.0;
  // Columns of cofactor(A) = det(A) A^-T are a1 x a2, a2 x a0, a0 x a1.
  const glm::dmat3 cof(glm::cross(a[1], a[2]), glm::cross(a[2], a[0]), glm::cross(a[0], a[1]));
  return {world, sign * cof, det < 0.0};
}

glm::vec3 place_point(const Placement& pl, const glm::vec3& p) {
  return glm::vec3(pl.world * glm::dvec4(glm::dvec3(p), 1.0));
}

// Unit transformed normal, or 0 when the result is zero or not finite.
glm::vec3 place_normal(const Placement& pl, const glm::vec3& n) {
  const glm::dvec3 m = pl.normal_matrix * glm::dvec3(n);
  const double len = glm::length(m);
  return len > 0.0 && std::isfinite(len) ? glm::vec3(m / len) : glm::vec3(0.0f);
}

// Appends one vertex of the primitive; returns its index in the soup.
std::uint32_t push_vertex(const Context& ctx, const Attributes& a, std::size_t v,
                          const Placement& pl, Soup& soup) {
  if (soup.positions.size() >= std::numeric_limits<std::uint32_t>::max()) {
    ctx.fail("", "more than 2^32 - 1 vertices");
  }
  soup.positions.push_back(place_point(pl, a.positions[v]));
  soup.normals.push_back(a.normals.empty() ? glm::vec3(0.0f) : place_normal(pl, a.normals[v]));
  soup.uvs.push_back(a.uvs.empty() ? glm::vec2(0.0f) : a.uvs[v]);
  return std::uint32_t(soup.positions.size() - 1);
}

// Triangles an index list of n entries gives in `mode` (TRIANGLES, TRIANGLE_STRIP or _FAN).
std::uint64_t triangle_count(int mode, std::size_t n) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return n / 3;
  return n >= 3 ? n - 2 : 0;
}

void check_triangle_limit(const Context& ctx, std::uint64_t more, const Soup& soup,
                          const std::string& where) {
  const std::uint64_t total = soup.triangles.size() + more;
  if (total > ctx.limits.max_triangles) {
    ctx.fail(where, "the scene would have " + std::to_string(total) +
                        " triangles, over the limit of " +
                        std::to_string(ctx.limits.max_triangles) + " (--max-triangles)");
  }
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The triangles whose three placed vertices are finite; the others are counted in the soup (one
// warning for the file, from finish_geometry).
std::vector<glm::uvec3> drop_non_finite(std::vector<glm::uvec3> triangles, const Attributes& a,
                                        const Placement& pl, const std::string& where, Soup& soup) {
  std::vector<char> ok(a.positions.size());
  for (std::size_t v = 0; v < ok.size(); ++v) ok[v] = finite(place_point(pl, a.positions[v]));
  std::size_t kept = 0;
  for (const glm::uvec3& t : triangles) {
    if (ok[t.x] && ok[t.y] && ok[t.z]) triangles[kept++] = t;
  }
  if (kept < triangles.size() && soup.non_finite_dropped == 0) soup.non_finite_where = where;
  soup.non_finite_dropped += triangles.size() - kept;
  triangles.resize(kept);
  return triangles;
}

void push_triangle(glm::uvec3 t, bool flip, std::uint32_t material, Soup& soup) {
  soup.triangles.push_back(flip ? glm::uvec3(t.x, t.z, t.y) : t);
  soup.triangle_material.push_back(material);
}

} // namespace

void append_primitive(const Context& ctx, std::size_t mesh, std::size_t primitive,
                      const glm::dmat4& world, std::uint32_t material, Soup& soup) {
  const tinygltf::Primitive& p = ctx.model.meshes[mesh].primitives[primitive];
  const std::string where = element("meshes", mesh) + element(".primitives", primitive);
  if (p.mode >= TINYGLTF_MODE_POINTS && p.mode <= TINYGLTF_MODE_LINE_STRIP) {
    ctx.warn("point and line primitives are not supported; skipped");
    return;
  }
  if (p.mode < TINYGLTF_MODE_TRIANGLES || p.mode > TINYGLTF_MODE_TRIANGLE_FAN) {
    ctx.fail(where, "invalid mode " + std::to_string(p.mode));
  }
  const Attributes a = read_attributes(ctx, p, where);
  const std::vector<std::uint32_t> indices = read_vertex_indices(ctx, p, a.positions.size(), where);
  check_triangle_limit(ctx, triangle_count(p.mode, indices.size()), soup, where);
  const Placement pl = placement(world);
  const std::vector<glm::uvec3> local =
      drop_non_finite(assemble(ctx, p.mode, indices, where), a, pl, where, soup);
  const std::uint64_t vertices = a.normals.empty() ? 3 * local.size() : a.positions.size();
  if (soup.positions.size() + vertices > 3 * ctx.limits.max_triangles) {
    ctx.fail(where, "the scene would have " + std::to_string(soup.positions.size() + vertices) +
                        " vertices, over the limit of 3 x " +
                        std::to_string(ctx.limits.max_triangles) + " (--max-triangles)");
  }
  soup.has_uvs = soup.has_uvs || !a.uvs.empty();
  if (!a.normals.empty()) {
    const std::uint32_t base = push_vertex(ctx, a, 0, pl, soup);
    for (std::size_t v = 1; v < a.positions.size(); ++v) push_vertex(ctx, a, v, pl, soup);
    for (const glm::uvec3& t : local) push_triangle(t + base, pl.flip, material, soup);
    return;
  }
  for (const glm::uvec3& t : local) { // flat normals: every triangle gets its own vertices
    const glm::uvec3 own{push_vertex(ctx, a, t.x, pl, soup), push_vertex(ctx, a, t.y, pl, soup),
                         push_vertex(ctx, a, t.z, pl, soup)}; // braces: evaluated in order
    push_triangle(own, pl.flip, material, soup);
  }
}

namespace {

// (p1 - p0) x (p2 - p0) in double precision: |c| = 2 area, direction = front face.
glm::dvec3 edge_cross(const Soup& s, const glm::uvec3& t) {
  const glm::dvec3 p0(s.positions[t.x]);
  return glm::cross(glm::dvec3(s.positions[t.y]) - p0, glm::dvec3(s.positions[t.z]) - p0);
}

Bounds triangle_bounds(const std::vector<glm::vec3>& positions,
                       const std::vector<glm::uvec3>& triangles) {
  Bounds b;
  for (const glm::uvec3& t : triangles) {
    b.extend(positions[t.x]);
    b.extend(positions[t.y]);
    b.extend(positions[t.z]);
  }
  return b;
}

// Keeps the non-degenerate triangles; returns how many were dropped.
std::size_t drop_degenerate(Soup& s) {
  const double diagonal = triangle_bounds(s.positions, s.triangles).diagonal();
  const double min_area = 1e-12 * diagonal * diagonal;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    const glm::uvec3 t = s.triangles[i];
    const bool repeated = t.x == t.y || t.y == t.z || t.z == t.x;
    if (repeated || !(0.5 * glm::length(edge_cross(s, t)) > min_area)) continue;
    s.triangles[kept] = t;
    s.triangle_material[kept++] = s.triangle_material[i];
  }
  const std::size_t dropped = s.triangles.size() - kept;
  s.triangles.resize(kept);
  s.triangle_material.resize(kept);
  return dropped;
}

// Vertices without a usable normal take the geometric normal of the first triangle using them.
void fill_normals(Soup& s) {
  for (const glm::uvec3& t : s.triangles) {
    const glm::vec3 n(glm::normalize(edge_cross(s, t)));
    for (std::uint32_t v : {t.x, t.y, t.z}) {
      if (s.normals[v] == glm::vec3(0.0f)) s.normals[v] = n;
    }
  }
}

// Removes vertices no triangle uses, keeping the order of the others.
void compact(Soup& s) {
  std::vector<std::uint32_t> remap(s.positions.size(), 0);
  for (const glm::uvec3& t : s.triangles) remap[t.x] = remap[t.y] = remap[t.z] = 1;
  std::uint32_t next = 0;
  for (std::size_t v = 0; v < s.positions.size(); ++v) {
    if (remap[v] == 0) continue;
    remap[v] = next;
    s.positions[next] = s.positions[v];
    s.normals[next] = s.normals[v];
    if (!s.vertex_node.empty()) s.vertex_node[next] = s.vertex_node[v];
    s.uvs[next++] = s.uvs[v];
  }
  s.positions.resize(next);
  s.normals.resize(next);
  s.uvs.resize(next);
  if (!s.vertex_node.empty()) s.vertex_node.resize(next);
  for (glm::uvec3& t : s.triangles) t = {remap[t.x], remap[t.y], remap[t.z]};
}

} // namespace

void finish_geometry(const Context& ctx, Soup soup, Scene& scene,
                     std::vector<std::uint32_t>* vertex_node) {
  if (soup.non_finite_dropped > 0) {
    ctx.warn(std::to_string(soup.non_finite_dropped) +
             " triangle(s) with a NaN or Inf vertex position dropped (the first in " +
             soup.non_finite_where + ")");
  }
  if (const std::size_t dropped = drop_degenerate(soup); dropped > 0) {
    ctx.warn(std::to_string(dropped) + " degenerate (zero-area) triangles dropped");
  }
  fill_normals(soup);
  compact(soup);
  scene.bounds = triangle_bounds(soup.positions, soup.triangles);
  scene.positions = std::move(soup.positions);
  scene.normals = std::move(soup.normals);
  if (soup.has_uvs) scene.uvs = std::move(soup.uvs);
  scene.triangles = std::move(soup.triangles);
  scene.triangle_material = std::move(soup.triangle_material);
  if (vertex_node) *vertex_node = std::move(soup.vertex_node);
}

} // namespace irad::gltf
