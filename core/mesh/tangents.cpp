#include "core/mesh/tangents.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <span>
#include <stdexcept>
#include <string>
#include <tuple>

namespace irad {

namespace {

constexpr std::uint32_t kNoIndex = ~0u;

// The reference's test for a usable magnitude: |x| > the smallest normal float.
bool not_zero(float x) {
  return std::fabs(x) > std::numeric_limits<float>::min();
}

glm::vec3 normalize_safe(const glm::vec3& v) {
  const float len = glm::length(v);
  return not_zero(len) ? (1.0f / len) * v : v;
}

// v made orthogonal to the unit (or zero) normal n, then normalised.
glm::vec3 project(const glm::vec3& v, const glm::vec3& n) {
  return normalize_safe(v - glm::dot(n, v) * n);
}

// One good (non-degenerate) triangle.
struct Face {
  std::uint32_t triangle = 0;       // index into the input triangles
  std::array<std::uint32_t, 3> v{}; // welded vertex of each corner
  glm::vec3 os{0.0f}, ot{0.0f};     // unit dp/du and dp/dv times the orientation sign
  bool orient = false;              // the uv map preserves orientation
  bool any = true;                  // no usable derivative: joins any group
  std::array<std::uint32_t, 3> neighbour{kNoIndex, kNoIndex, kNoIndex}; // across edge (c, c + 1)
  std::array<std::uint32_t, 3> group{kNoIndex, kNoIndex, kNoIndex};     // per corner
};

// The faces around one welded vertex that share a tangent frame: Groups::faces[begin, end), in
// the order they joined.
struct Group {
  std::uint32_t vertex = 0;
  bool orient = false;
  std::uint32_t begin = 0, end = 0;
};

struct Groups {
  std::vector<Group> groups;
  std::vector<std::uint32_t> faces; // every group's faces, one group after the other
};

// A corner's frame: the tangent and the orientation, set where a group (or a copy) gave one.
struct Frame {
  glm::vec3 os{1.0f, 0.0f, 0.0f};
  bool orient = false;
  bool set = false;
};

// The working mesh: unit normals, uvs in the reference's convention (u, -v), welded corners.
struct Mesh {
  const std::vector<glm::vec3>& positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint32_t> weld; // per vertex: its representative
};

void check_input(std::size_t n, std::size_t normals, std::size_t uvs,
                 const std::vector<glm::uvec3>& triangles) {
  if (normals != n || uvs != n)
    throw std::invalid_argument("mikktspace_tangents: positions, normals and uvs differ in size");
  for (const glm::uvec3& t : triangles)
    if (t.x >= n || t.y >= n || t.z >= n)
      throw std::invalid_argument("mikktspace_tangents: vertex index out of range");
}

// Representative per vertex: the first of the vertices whose position, normal and uv have the
// same bits (the reference welds by hashing the bits, then comparing).
std::vector<std::uint32_t> weld(const std::vector<glm::vec3>& p, const std::vector<glm::vec3>& n,
                                const std::vector<glm::vec2>& uv) {
  using Key = std::array<std::uint32_t, 8>;
  std::vector<Key> keys(p.size());
  const auto b = [](float x) { return std::bit_cast<std::uint32_t>(x); };
  for (std::size_t v = 0; v < p.size(); ++v)
    keys[v] = {b(p[v].x), b(p[v].y), b(p[v].z),  b(n[v].x),
               b(n[v].y), b(n[v].z), b(uv[v].x), b(uv[v].y)};
  std::vector<std::uint32_t> order(p.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
    return keys[x] != keys[y] ? keys[x] < keys[y] : x < y;
  });
  std::vector<std::uint32_t> rep(p.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    rep[order[i]] = i > 0 && keys[order[i]] == keys[order[i - 1]] ? rep[order[i - 1]] : order[i];
  return rep;
}

Mesh make_mesh(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
               const std::vector<glm::vec2>& uvs) {
  Mesh m{positions, {}, {}, weld(positions, normals, uvs)};
  m.normals.reserve(normals.size());
  for (const glm::vec3& n : normals) {
    const float len = glm::length(n);
    m.normals.push_back(len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0.0f));
  }
  m.uvs.reserve(uvs.size());
  for (const glm::vec2& uv : uvs) m.uvs.emplace_back(uv.x, -uv.y);
  return m;
}

// The reference's per-triangle derivatives (its equations 18 and 19) and flags: a triangle has
// usable derivatives where the uv area and |dp/du| / area and |dp/dv| / area are not zero.
Face make_face(const Mesh& m, std::uint32_t triangle, const std::array<std::uint32_t, 3>& v) {
  Face f;
  f.triangle = triangle;
  f.v = v;
  const glm::vec2 t21 = m.uvs[v[1]] - m.uvs[v[0]], t31 = m.uvs[v[2]] - m.uvs[v[0]];
  const glm::vec3 d1 = m.positions[v[1]] - m.positions[v[0]];
  const glm::vec3 d2 = m.positions[v[2]] - m.positions[v[0]];
  const float area = t21.x * t31.y - t21.y * t31.x; // twice the signed uv area
  const glm::vec3 os = t31.y * d1 - t21.y * d2;
  const glm::vec3 ot = -t31.x * d1 + t21.x * d2;
  f.orient = area > 0.0f;
  if (!not_zero(area)) return f;
  const float len_s = glm::length(os), len_t = glm::length(ot);
  const float sign = f.orient ? 1.0f : -1.0f;
  if (not_zero(len_s)) f.os = (sign / len_s) * os;
  if (not_zero(len_t)) f.ot = (sign / len_t) * ot;
  f.any = !(not_zero(len_s / std::fabs(area)) && not_zero(len_t / std::fabs(area)));
  return f;
}

// Edge neighbours: faces sharing an edge in opposite directions. Entries are taken in the order
// (smaller vertex, larger vertex, face); each unpaired one pairs with the first later entry of
// the same edge that runs the other way and is unpaired (the reference's BuildNeighborsFast).
void link_neighbours(std::vector<Face>& faces) {
  struct Entry {
    std::uint32_t lo, hi, face, edge;
  };
  std::vector<Entry> entries;
  entries.reserve(3 * faces.size());
  for (std::uint32_t f = 0; f < faces.size(); ++f)
    for (std::uint32_t e = 0; e < 3; ++e) {
      const std::uint32_t a = faces[f].v[e], b = faces[f].v[(e + 1) % 3];
      entries.push_back({std::min(a, b), std::max(a, b), f, e});
    }
  std::sort(entries.begin(), entries.end(), [](const Entry& x, const Entry& y) {
    return std::tie(x.lo, x.hi, x.face, x.edge) < std::tie(y.lo, y.hi, y.face, y.edge);
  });
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const Entry& a = entries[i];
    Face& fa = faces[a.face];
    if (fa.neighbour[a.edge] != kNoIndex) continue;
    const std::uint32_t from = fa.v[a.edge];
    for (std::size_t j = i + 1; j < entries.size(); ++j) {
      const Entry& b = entries[j];
      if (b.lo != a.lo || b.hi != a.hi) break;
      Face& fb = faces[b.face];
      if (fb.v[b.edge] == from || fb.neighbour[b.edge] != kNoIndex) continue; // same direction
      fa.neighbour[a.edge] = b.face;
      fb.neighbour[b.edge] = a.face;
      break;
    }
  }
}

int corner_of(const Face& f, std::uint32_t vertex) {
  return f.v[0] == vertex ? 0 : f.v[1] == vertex ? 1 : 2;
}

// Grows group g from face `start` through the edges around g.vertex, depth first in the
// reference's order (AssignRecur: the neighbour across edge (c, c + 1), then across (c - 1, c)).
// A face already in a group there, or of the other orientation, stops the walk; a face without
// usable derivatives takes the group's orientation when it joins its first group.
void grow(std::vector<Face>& faces, std::uint32_t gi, const Group& g, std::uint32_t start,
          std::vector<std::uint32_t>& members, std::vector<std::uint32_t>& stack) {
  stack.assign(1, start);
  while (!stack.empty()) {
    const std::uint32_t fi = stack.back();
    stack.pop_back();
    Face& f = faces[fi];
    const int c = corner_of(f, g.vertex);
    if (f.group[c] != kNoIndex) continue;
    if (f.any && f.group[0] == kNoIndex && f.group[1] == kNoIndex && f.group[2] == kNoIndex)
      f.orient = g.orient;
    if (f.orient != g.orient) continue;
    members.push_back(fi);
    f.group[c] = gi;
    const std::uint32_t left = f.neighbour[c], right = f.neighbour[(c + 2) % 3];
    if (right != kNoIndex) stack.push_back(right);
    if (left != kNoIndex) stack.push_back(left);
  }
}

// One group per corner of a good face not yet grouped (the reference's Build4RuleGroups).
Groups build_groups(std::vector<Face>& faces) {
  Groups out;
  out.faces.reserve(3 * faces.size());
  std::vector<std::uint32_t> stack;
  for (std::uint32_t f = 0; f < faces.size(); ++f)
    for (int c = 0; c < 3; ++c) {
      if (faces[f].any || faces[f].group[c] != kNoIndex) continue;
      Group g{faces[f].v[c], faces[f].orient, std::uint32_t(out.faces.size()), 0};
      grow(faces, std::uint32_t(out.groups.size()), g, f, out.faces, stack);
      g.end = std::uint32_t(out.faces.size());
      out.groups.push_back(g);
    }
  return out;
}

// The frame of `members` (ascending face indices) at `vertex`: the angle-weighted sum of their
// projected unit dp/du (the reference's EvalTspace; faces without derivatives add nothing).
glm::vec3 eval_tangent(const Mesh& m, const std::vector<Face>& faces,
                       const std::vector<std::uint32_t>& members, std::uint32_t vertex) {
  const glm::vec3& n = m.normals[vertex];
  glm::vec3 sum(0.0f);
  for (std::uint32_t fi : members) {
    const Face& f = faces[fi];
    if (f.any) continue;
    const int c = corner_of(f, vertex);
    const glm::vec3& p = m.positions[f.v[c]];
    const glm::vec3 e1 = project(m.positions[f.v[(c + 2) % 3]] - p, n);
    const glm::vec3 e2 = project(m.positions[f.v[(c + 1) % 3]] - p, n);
    const float angle = std::acos(std::clamp(glm::dot(e1, e2), -1.0f, 1.0f));
    sum += angle * project(f.os, n);
  }
  return normalize_safe(sum);
}

// Whether every pair of faces in the group passes the reference's sub-group test at threshold
// cos(180 deg) = -1 (dot(os_a, os_b) > -1 and dot(ot_a, ot_b) > -1) for sure: all projected
// derivatives within 89.4 degrees of the first face's exclude exactly opposite pairs.
bool one_subgroup(const std::vector<glm::vec3>& os, const std::vector<glm::vec3>& ot,
                  const std::vector<char>& any) {
  std::size_t k = 0;
  while (k < any.size() && any[k]) ++k;
  if (k == any.size()) return true;
  for (std::size_t j = 0; j < any.size(); ++j)
    if (!any[j] && (glm::dot(os[k], os[j]) <= 0.01f || glm::dot(ot[k], ot[j]) <= 0.01f))
      return false;
  return true;
}

// Per-group working arrays, reused from group to group.
struct Scratch {
  std::vector<glm::vec3> os, ot; // the group's faces' derivatives projected at the vertex
  std::vector<char> any;
  std::vector<std::uint32_t> members;
  std::vector<std::pair<std::vector<std::uint32_t>, glm::vec3>> subgroups;
};

// The frames of group g's corners (the reference's GenerateTSpaces at 180 degrees): each face's
// corner takes the frame of the faces whose projected derivatives are not exactly opposite to
// its own (all of them unless such a pair exists).
void group_frames(const Mesh& m, const std::vector<Face>& faces, const Group& g,
                  std::span<const std::uint32_t> group, Scratch& s, std::vector<Frame>& frames) {
  const glm::vec3& n = m.normals[g.vertex];
  const std::size_t k = group.size();
  s.os.resize(k);
  s.ot.resize(k);
  s.any.resize(k);
  for (std::size_t i = 0; i < k; ++i) {
    s.os[i] = project(faces[group[i]].os, n);
    s.ot[i] = project(faces[group[i]].ot, n);
    s.any[i] = faces[group[i]].any;
  }
  const auto output = [&](std::size_t i, const glm::vec3& tangent) {
    const Face& f = faces[group[i]];
    frames[3 * std::size_t(f.triangle) + std::size_t(corner_of(f, g.vertex))] = {tangent, g.orient,
                                                                                 true};
  };
  s.members.assign(group.begin(), group.end());
  std::sort(s.members.begin(), s.members.end());
  if (one_subgroup(s.os, s.ot, s.any)) {
    const glm::vec3 tangent = eval_tangent(m, faces, s.members, g.vertex);
    for (std::size_t i = 0; i < k; ++i) output(i, tangent);
    return;
  }
  s.subgroups.clear();
  for (std::size_t i = 0; i < k; ++i) {
    s.members.clear();
    for (std::size_t j = 0; j < k; ++j)
      if (s.any[i] || s.any[j] || i == j ||
          (glm::dot(s.os[i], s.os[j]) > -1.0f && glm::dot(s.ot[i], s.ot[j]) > -1.0f))
        s.members.push_back(group[j]);
    std::sort(s.members.begin(), s.members.end());
    auto it = std::find_if(s.subgroups.begin(), s.subgroups.end(),
                           [&](const auto& sub) { return sub.first == s.members; });
    if (it == s.subgroups.end())
      it = s.subgroups.insert(s.subgroups.end(),
                              {s.members, eval_tangent(m, faces, s.members, g.vertex)});
    output(i, it->second);
  }
}

// Corners of degenerate triangles copy the frame of the first good corner of the same welded
// vertex (the reference's DegenEpilogue), where there is one.
void copy_to_degenerate(const std::vector<Face>& faces,
                        const std::vector<std::uint32_t>& degenerate, const Mesh& m,
                        const std::vector<glm::uvec3>& triangles, std::vector<Frame>& frames) {
  if (degenerate.empty()) return;
  std::vector<std::uint32_t> first(m.weld.size(), kNoIndex);
  for (const Face& f : faces)
    for (int c = 0; c < 3; ++c)
      if (first[f.v[c]] == kNoIndex) first[f.v[c]] = 3 * f.triangle + std::uint32_t(c);
  for (std::uint32_t t : degenerate)
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t source = first[m.weld[triangles[t][c]]];
      if (source != kNoIndex) frames[3 * std::size_t(t) + std::size_t(c)] = frames[source];
    }
}

} // namespace

glm::vec3 any_tangent(const glm::vec3& n) {
  const glm::vec3 a =
      std::fabs(n.x) < 0.9f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  const glm::vec3 t = a - glm::dot(a, n) * n;
  const float len = glm::length(t);
  return len > 1e-6f ? t / len : a;
}

std::vector<glm::vec4> mikktspace_tangents(const std::vector<glm::vec3>& positions,
                                           const std::vector<glm::vec3>& normals,
                                           const std::vector<glm::vec2>& uvs,
                                           const std::vector<glm::uvec3>& triangles) {
  check_input(positions.size(), normals.size(), uvs.size(), triangles);
  const Mesh m = make_mesh(positions, normals, uvs);
  std::vector<Face> faces;
  std::vector<std::uint32_t> degenerate;
  faces.reserve(triangles.size());
  for (std::uint32_t t = 0; t < triangles.size(); ++t) {
    const std::array<std::uint32_t, 3> v{m.weld[triangles[t].x], m.weld[triangles[t].y],
                                         m.weld[triangles[t].z]};
    const glm::vec3 &p0 = positions[v[0]], &p1 = positions[v[1]], &p2 = positions[v[2]];
    if (p0 == p1 || p1 == p2 || p2 == p0)
      degenerate.push_back(t);
    else
      faces.push_back(make_face(m, t, v));
  }
  link_neighbours(faces);
  std::vector<Frame> frames(3 * triangles.size());
  const Groups groups = build_groups(faces);
  Scratch scratch;
  for (const Group& g : groups.groups)
    group_frames(m, faces, g, std::span(groups.faces).subspan(g.begin, g.end - g.begin), scratch,
                 frames);
  copy_to_degenerate(faces, degenerate, m, triangles, frames);

  std::vector<glm::vec4> out(frames.size());
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const glm::vec3& n = m.normals[triangles[k / 3][int(k % 3)]];
    glm::vec3 t = frames[k].os - glm::dot(frames[k].os, n) * n;
    const float len = glm::length(t);
    t = frames[k].set && len > 1e-6f && std::isfinite(len) ? t / len : any_tangent(n);
    out[k] = glm::vec4(t, frames[k].set && !frames[k].orient ? -1.0f : 1.0f);
  }
  return out;
}

TangentVertices split_by_tangent(std::size_t vertex_count, const std::vector<glm::uvec3>& triangles,
                                 const std::vector<glm::vec4>& corner_tangents) {
  if (corner_tangents.size() != 3 * triangles.size())
    throw std::invalid_argument("split_by_tangent: " + std::to_string(corner_tangents.size()) +
                                " corner tangents for " + std::to_string(triangles.size()) +
                                " triangles");
  TangentVertices out;
  out.source.resize(vertex_count);
  std::iota(out.source.begin(), out.source.end(), 0u);
  out.tangents.assign(vertex_count, glm::vec4(0.0f));
  out.triangles = triangles;
  std::vector<char> used(vertex_count, 0);
  std::vector<std::uint32_t> next(vertex_count, kNoIndex); // chain of a vertex's copies
  for (std::size_t k = 0; k < corner_tangents.size(); ++k) {
    std::uint32_t& index = out.triangles[k / 3][int(k % 3)];
    if (index >= vertex_count) throw std::invalid_argument("split_by_tangent: index out of range");
    const glm::vec4& t = corner_tangents[k];
    std::uint32_t v = index;
    if (!used[v]) {
      used[v] = 1;
      out.tangents[v] = t;
      continue;
    }
    while (out.tangents[v] != t && next[v] != kNoIndex) v = next[v];
    if (out.tangents[v] != t) { // a new copy at the end of the chain
      next[v] = std::uint32_t(out.source.size());
      v = next[v];
      out.source.push_back(index);
      out.tangents.push_back(t);
      next.push_back(kNoIndex);
    }
    index = v;
  }
  return out;
}

namespace {

// Every corner its own vertex with its triangle's normal.
TangentVertices flat_tangent_vertices(const std::vector<glm::vec3>& positions,
                                      const std::vector<glm::vec2>& uvs,
                                      const std::vector<glm::uvec3>& triangles) {
  if (!uvs.empty() && uvs.size() != positions.size())
    throw std::invalid_argument("tangent_vertices: positions and uvs differ in size");
  TangentVertices out;
  out.source.reserve(3 * triangles.size());
  for (const glm::uvec3& t : triangles) out.source.insert(out.source.end(), {t.x, t.y, t.z});
  std::vector<glm::vec3> p, n;
  std::vector<glm::vec2> uv;
  p.reserve(out.source.size());
  n.reserve(out.source.size());
  uv.reserve(out.source.size());
  for (std::size_t k = 0; k < out.source.size(); ++k) {
    if (out.source[k] >= positions.size())
      throw std::invalid_argument("tangent_vertices: vertex index out of range");
    p.push_back(positions[out.source[k]]);
    uv.push_back(uvs.empty() ? glm::vec2(0.0f) : uvs[out.source[k]]);
    if (k % 3 == 2) {
      const glm::vec3 c = glm::cross(p[k - 1] - p[k - 2], p[k] - p[k - 2]);
      n.insert(n.end(), 3, c); // normalised by mikktspace_tangents
    }
  }
  for (std::uint32_t t = 0; t < triangles.size(); ++t)
    out.triangles.emplace_back(3 * t, 3 * t + 1, 3 * t + 2);
  out.tangents = mikktspace_tangents(p, n, uv, out.triangles);
  return out;
}

} // namespace

TangentVertices tangent_vertices(const std::vector<glm::vec3>& positions,
                                 const std::vector<glm::vec3>& normals,
                                 const std::vector<glm::vec2>& uvs,
                                 const std::vector<glm::uvec3>& triangles) {
  if (normals.empty()) return flat_tangent_vertices(positions, uvs, triangles);
  if (uvs.empty()) {
    const std::vector<glm::vec2> zero(positions.size(), glm::vec2(0.0f));
    return split_by_tangent(positions.size(), triangles,
                            mikktspace_tangents(positions, normals, zero, triangles));
  }
  return split_by_tangent(positions.size(), triangles,
                          mikktspace_tangents(positions, normals, uvs, triangles));
}

} // namespace irad
