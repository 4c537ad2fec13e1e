#include "core/gltf/read/geometry.h"

#include "core/gltf/decode/codecs.h"
#include "core/gltf/read/accessors.h"
#include "core/gltf/read/skins.h"
#include "core/gltf/read/triangle_list.h"
#include "core/mesh/tangents.h"
#include "core/util/freed_memory.h"
#include "core/util/parallel_rows.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <optional>

namespace irad::gltf {

namespace {

// A primitive's vertex attributes in its mesh's frame (morphed), or in the world when skinned.
struct Attributes {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // empty without NORMAL
  std::vector<glm::vec2> uvs;      // empty without the set of uv slot 0
  std::vector<glm::vec2> uvs1;     // empty without the set of uv slot 1
  std::vector<glm::vec4> colors;   // empty without COLOR_0
  std::vector<glm::vec4> tangents; // empty without tangents (TANGENT or generated)
};

// The accessor index of attribute `name` of `attributes` (an object), or nullopt.
std::optional<std::uint64_t> attribute(const json& attributes, const std::string& name) {
  return index_member(attributes, name.c_str());
}

template <class T>
void require_count(const Context& ctx, const std::vector<T>& values, std::size_t n,
                   const std::string& where, const std::string& name) {
  if (values.size() != n) {
    ctx.fail(where + ".attributes." + name,
             fmt::format("{} elements, POSITION has {}", values.size(), n));
  }
}

// TANGENT: VEC4 of floats (normalized bytes or shorts with KHR_mesh_quantization).
std::vector<glm::vec4> read_tangents(const Context& ctx, std::uint64_t accessor,
                                     const std::string& use) {
  const Values v = read_values(ctx, accessor, use, {"VEC4"}, {kFloat, kByte, kShort}, true);
  std::vector<glm::vec4> out(v.count());
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = {v.data[4 * i], v.data[4 * i + 1], v.data[4 * i + 2], v.data[4 * i + 3]};
  return out;
}

std::vector<glm::vec2> read_uv_set(const Context& ctx, const json& attrs, int set, std::size_t n,
                                   const std::string& where) {
  if (set < 0) return {};
  const std::string name = "TEXCOORD_" + std::to_string(set);
  const auto a = attribute(attrs, name);
  if (!a) {
    ctx.warn(where + ": its material's textures read " + name +
             ", which the primitive lacks; (0, 0) is used");
    return {};
  }
  std::vector<glm::vec2> uv = read_texcoords(ctx, *a, where + ".attributes." + name);
  require_count(ctx, uv, n, where, name);
  return uv;
}

// The morph targets' displacements (glTF 3.7.2.2), [target][vertex]; normals' and tangents'
// empty when the primitive has none.
struct Targets {
  std::vector<std::vector<glm::vec3>> positions;
  std::vector<std::vector<glm::vec3>> normals;
  std::vector<std::vector<glm::vec3>> tangents;
};

Targets read_targets(const Context& ctx, const json& p, std::size_t n, bool with_normals,
                     bool with_tangents, const std::string& where) {
  Targets out;
  const json* targets = member(p, "targets");
  if (!targets || !targets->is_array()) return out;
  for (std::size_t t = 0; t < targets->size(); ++t) {
    const json& target = (*targets)[t];
    const std::string tw = where + ".targets[" + std::to_string(t) + "]";
    auto read = [&](const char* name) {
      const auto a = attribute(target, name);
      if (!a) return std::vector<glm::vec3>(n, glm::vec3(0.0f));
      std::vector<glm::vec3> d = read_vec3(ctx, *a, tw + "." + name);
      if (d.size() != n)
        ctx.fail(tw + "." + name, fmt::format("{} elements, POSITION has {}", d.size(), n));
      return d;
    };
    out.positions.push_back(read("POSITION"));
    if (with_normals) out.normals.push_back(read("NORMAL"));
    if (with_tangents) out.tangents.push_back(read("TANGENT"));
  }
  return out;
}

// p += sum_i w_i dp_i (and normals and tangents' xyz alike).
void apply_morph(const Targets& t, const std::vector<double>& weights, Attributes& a) {
  for (std::size_t i = 0; i < t.positions.size() && i < weights.size(); ++i) {
    const float w = float(weights[i]);
    if (w == 0.0f) continue;
    for (std::size_t v = 0; v < a.positions.size(); ++v) a.positions[v] += w * t.positions[i][v];
    if (i < t.normals.size() && !a.normals.empty())
      for (std::size_t v = 0; v < a.normals.size(); ++v) a.normals[v] += w * t.normals[i][v];
    if (i < t.tangents.size() && !a.tangents.empty())
      for (std::size_t v = 0; v < a.tangents.size(); ++v)
        a.tangents[v] += glm::vec4(w * t.tangents[i][v], 0.0f);
  }
}

// JOINTS_0 and WEIGHTS_0 of a skinned primitive, per vertex.
struct Influences {
  std::vector<glm::uvec4> joints;
  std::vector<glm::vec4> weights;
};

Influences read_influences(const Context& ctx, const json& attrs, std::size_t n,
                           std::size_t joint_count, const std::string& where) {
  Influences out;
  const auto j = attribute(attrs, "JOINTS_0");
  const auto w = attribute(attrs, "WEIGHTS_0");
  if (!j || !w) {
    ctx.warn(where + ": a skinned mesh without JOINTS_0 and WEIGHTS_0; left unskinned");
    return out;
  }
  const Values jv = read_values(ctx, *j, where + ".attributes.JOINTS_0", {"VEC4"},
                                {kUnsignedByte, kUnsignedShort});
  const Values wv = read_values(ctx, *w, where + ".attributes.WEIGHTS_0", {"VEC4"},
                                {kUnsignedByte, kUnsignedShort, kFloat}, true);
  if (jv.count() != n || wv.count() != n)
    ctx.fail(where + ".attributes", "JOINTS_0 and WEIGHTS_0 must have POSITION's count");
  out.joints.resize(n);
  out.weights.resize(n);
  for (std::size_t v = 0; v < n; ++v)
    for (int k = 0; k < 4; ++k) {
      const float weight = wv.data[4 * v + std::size_t(k)];
      const std::uint32_t joint = std::uint32_t(jv.data[4 * v + std::size_t(k)]);
      if (weight != 0.0f && joint >= joint_count)
        ctx.fail(where + ".attributes.JOINTS_0",
                 fmt::format("joint {} out of range ({} joints)", joint, joint_count));
      out.joints[v][k] = joint;
      out.weights[v][k] = std::isfinite(weight) ? std::max(weight, 0.0f) : 0.0f;
    }
  return out;
}

// Linear blend skinning: p' = sum_k w_k M_{j_k} p with M = joint world x inverse bind matrix,
// normals by the cofactor of the blended matrix (glTF 3.7.3), tangents by its 3x3 block B
// (t' = B t, w' = w sign(det B)). Weights are renormalised to sum 1; a vertex without influence
// stays where it is.
void apply_skin(const Influences& inf, const std::vector<glm::dmat4>& joints, Attributes& a) {
  for (std::size_t v = 0; v < inf.joints.size(); ++v) {
    glm::dmat4 m(0.0);
    double total = 0.0;
    for (int k = 0; k < 4; ++k) {
      const double weight = double(inf.weights[v][k]);
      if (weight == 0.0) continue;
      m += weight * joints[inf.joints[v][k]];
      total += weight;
    }
    if (!(total > 0.0)) continue;
    m /= total;
    a.positions[v] = glm::vec3(m * glm::dvec4(glm::dvec3(a.positions[v]), 1.0));
    if (!a.normals.empty()) {
      const glm::dmat3 b(m);
      const glm::dmat3 cof(glm::cross(b[1], b[2]), glm::cross(b[2], b[0]), glm::cross(b[0], b[1]));
      a.normals[v] =
          glm::vec3((glm::determinant(b) < 0.0 ? -1.0 : 1.0) * (cof * glm::dvec3(a.normals[v])));
    }
    if (!a.tangents.empty()) {
      const glm::dmat3 b(m);
      const float w = glm::determinant(b) < 0.0 ? -a.tangents[v].w : a.tangents[v].w;
      a.tangents[v] = glm::vec4(glm::vec3(b * glm::dvec3(glm::vec3(a.tangents[v]))), w);
    }
  }
}

// Decodes a KHR_draco_mesh_compression primitive: its attributes become the decoded data of the
// primitive's accessors (ctx.decoded_accessors); returns the decoded indices.
std::vector<std::uint32_t> decode_draco(const Context& ctx, const json& ext, const json& attrs,
                                        const std::string& where) {
  const std::string ew = where + ".extensions.KHR_draco_mesh_compression";
  const auto view = index_member(ext, "bufferView");
  if (!view) ctx.fail(ew, "no bufferView");
  const std::string vname = element("bufferViews", std::size_t(*view));
  const ViewBytes bytes = view_bytes(ctx, *view, ew);
  try {
    const DracoMesh mesh(bytes.data, bytes.length);
    const json* ids = member(ext, "attributes");
    for (const auto& [name, value] : attrs.items()) {
      const auto accessor = as_index(value);
      const auto id = ids ? index_member(*ids, name.c_str()) : std::nullopt;
      if (!accessor || !id) continue;
      const json& a = ctx.at("accessors", *accessor, where + ".attributes." + name, "accessor");
      const std::size_t components = component_count(string_member(a, "type"));
      if (components == 0) ctx.fail(element("accessors", std::size_t(*accessor)), "unknown type");
      ctx.decoded_accessors[std::size_t(*accessor)] =
          mesh.attribute(int(*id), int(number_member(a, "componentType", 0)), int(components),
                         bool_member(a, "normalized", false));
    }
    return mesh.indices();
  } catch (const CodecError& e) {
    ctx.fail(vname, std::string("KHR_draco_mesh_compression: ") + e.what());
  }
}

// A primitive's attributes as the file stores them (mesh frame, unmorphed, unskinned), with its
// morph targets and skin influences.
struct RawPrimitive {
  Attributes a;
  Targets targets;
  Influences influences;
};

Attributes read_attributes(const Context& ctx, const json& p, UvSets uv, const std::string& where) {
  Attributes a;
  const json* attrs_ptr = member(p, "attributes");
  const json& attrs = attrs_ptr ? *attrs_ptr : json::object();
  const auto position = attribute(attrs, "POSITION");
  a.positions = read_vec3(ctx, *position, where + ".attributes.POSITION");
  const std::size_t n = a.positions.size();
  if (const auto normal = attribute(attrs, "NORMAL")) {
    a.normals = read_vec3(ctx, *normal, where + ".attributes.NORMAL");
    require_count(ctx, a.normals, n, where, "NORMAL");
  }
  a.uvs = read_uv_set(ctx, attrs, uv.slot0, n, where);
  a.uvs1 = read_uv_set(ctx, attrs, uv.slot1, n, where);
  if (const auto color = attribute(attrs, "COLOR_0")) {
    a.colors = read_colors(ctx, *color, where + ".attributes.COLOR_0");
    require_count(ctx, a.colors, n, where, "COLOR_0");
  }
  const auto tangent = attribute(attrs, "TANGENT");
  if (uv.tangent_slot >= 0 && tangent) {
    a.tangents = read_tangents(ctx, *tangent, where + ".attributes.TANGENT");
    require_count(ctx, a.tangents, n, where, "TANGENT");
  }
  return a;
}

RawPrimitive read_primitive(const Context& ctx, const json& p, const PrimitivePose& pose, UvSets uv,
                            const std::string& where) {
  RawPrimitive raw;
  raw.a = read_attributes(ctx, p, uv, where);
  const std::size_t n = raw.a.positions.size();
  if (!pose.morph_weights.empty())
    raw.targets = read_targets(ctx, p, n, !raw.a.normals.empty(), !raw.a.tangents.empty(), where);
  if (pose.skin)
    raw.influences =
        read_influences(ctx, *member(p, "attributes"), n, pose.skin->matrices.size(), where);
  return raw;
}

template <class T>
void gather(std::vector<T>& values, const std::vector<std::uint32_t>& source) {
  if (values.empty()) return;
  std::vector<T> out;
  out.reserve(source.size());
  for (std::uint32_t v : source) out.push_back(values[v]);
  values = std::move(out);
}

// The primitive's vertices replaced by source[0], source[1], ... (every per-vertex array:
// attributes, morph targets, skin influences).
void gather(RawPrimitive& raw, const std::vector<std::uint32_t>& source) {
  for (auto* v : {&raw.a.positions, &raw.a.normals}) gather(*v, source);
  for (auto* v : {&raw.a.uvs, &raw.a.uvs1}) gather(*v, source);
  for (auto* v : {&raw.a.colors, &raw.a.tangents}) gather(*v, source);
  for (auto* targets : {&raw.targets.positions, &raw.targets.normals, &raw.targets.tangents})
    for (std::vector<glm::vec3>& t : *targets) gather(t, source);
  gather(raw.influences.joints, source);
  gather(raw.influences.weights, source);
}

// MikkTSpace tangents (core/mesh/tangents.h tangent_vertices) of the primitive as the file
// stores it, following the texture coordinates of uv slot `slot`: its vertices become the ones
// tangent_vertices gives (copies where corners disagree; one per corner without NORMAL), and
// `triangles` is re-indexed.
void generate_tangents(RawPrimitive& raw, int slot, std::vector<glm::uvec3>& triangles) {
  TangentVertices tv = tangent_vertices(raw.a.positions, raw.a.normals,
                                        slot == 0 ? raw.a.uvs : raw.a.uvs1, triangles);
  gather(raw, tv.source);
  raw.a.tangents = std::move(tv.tangents);
  triangles = std::move(tv.triangles);
}

// The attributes at rest: morphed by the default weights, then skinned.
Attributes posed_attributes(const RawPrimitive& raw, const PrimitivePose& pose) {
  Attributes a = raw.a;
  apply_morph(raw.targets, pose.morph_weights, a);
  if (pose.skin && !raw.influences.joints.empty())
    apply_skin(raw.influences, pose.skin->matrices, a);
  return a;
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

// (normalize(A t.xyz), sign(t.w) sign(det A)): a tangent follows the surface's points, and a
// mirroring A flips the bitangent w cross(n, t) back onto A's image of the old one. 0 when A t.xyz
// is zero or not finite.
glm::vec4 place_tangent(const Placement& pl, const glm::vec4& t) {
  const glm::dvec3 m = glm::dmat3(pl.world) * glm::dvec3(glm::vec3(t));
  const double len = glm::length(m);
  if (!(len > 0.0 && std::isfinite(len))) return glm::vec4(0.0f);
  return glm::vec4(glm::vec3(m / len), (t.w < 0.0f) != pl.flip ? -1.0f : 1.0f);
}

// Room for `n` more vertices in every array the soup keeps, the optional sets opened by the first
// primitive that has them (the vertices before it given their defaults: uv (0, 0), colour 1,
// tangent 0); returns the index of the first new vertex. Fails past 2^32 - 1 vertices.
std::size_t open_vertices(const Context& ctx, const Attributes& a, std::size_t n, Soup& soup) {
  const std::size_t base = soup.positions.size();
  if (base + n > std::numeric_limits<std::uint32_t>::max()) {
    ctx.fail("", "more than 2^32 - 1 vertices");
  }
  soup.positions.resize(base + n);
  soup.normals.resize(base + n);
  if (!a.uvs.empty() || !soup.uvs.empty()) soup.uvs.resize(base + n, glm::vec2(0.0f));
  if (!a.uvs1.empty() || !soup.uvs1.empty()) soup.uvs1.resize(base + n, glm::vec2(0.0f));
  if (!a.colors.empty() || !soup.colors.empty()) soup.colors.resize(base + n, glm::vec4(1.0f));
  if (!a.tangents.empty() || !soup.tangents.empty())
    soup.tangents.resize(base + n, glm::vec4(0.0f));
  return base;
}

// Writes the primitive's vertex v, placed, into soup vertex `at` (opened by open_vertices): the
// attributes it lacks keep their defaults (a normal 0: finish_geometry fills it).
void place_vertex(const Attributes& a, std::size_t v, const Placement& pl, std::size_t at,
                  Soup& soup) {
  soup.positions[at] = place_point(pl, a.positions[v]);
  soup.normals[at] = a.normals.empty() ? glm::vec3(0.0f) : place_normal(pl, a.normals[v]);
  if (!a.uvs.empty()) soup.uvs[at] = a.uvs[v];
  if (!a.uvs1.empty()) soup.uvs1[at] = a.uvs1[v];
  if (!a.colors.empty()) soup.colors[at] = a.colors[v];
  if (!a.tangents.empty()) soup.tangents[at] = place_tangent(pl, a.tangents[v]);
}

// Appends one vertex of the primitive; returns its index in the soup.
std::uint32_t push_vertex(const Context& ctx, const Attributes& a, std::size_t v,
                          const Placement& pl, Soup& soup) {
  const std::size_t at = open_vertices(ctx, a, 1, soup);
  place_vertex(a, v, pl, at, soup);
  return static_cast<std::uint32_t>(at);
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The triangles whose three placed vertices are finite; the others are counted in the soup (one
// warning for the file, from finish_geometry).
std::vector<glm::uvec3> drop_non_finite(std::vector<glm::uvec3> triangles, const Attributes& a,
                                        const Placement& pl, const std::string& where, Soup& soup) {
  std::vector<char> ok(a.positions.size());
  parallel_chunks(ok.size(), [&](std::size_t first, std::size_t end) {
    for (std::size_t v = first; v < end; ++v) ok[v] = finite(place_point(pl, a.positions[v]));
  });
  std::size_t kept = 0;
  for (const glm::uvec3& t : triangles) {
    if (ok[t.x] && ok[t.y] && ok[t.z]) triangles[kept++] = t;
  }
  if (kept < triangles.size() && soup.non_finite_dropped == 0) soup.non_finite_where = where;
  soup.non_finite_dropped += triangles.size() - kept;
  triangles.resize(kept);
  return triangles;
}

// Appends every vertex of the primitive, each placed as push_vertex places one, on all cores;
// returns the soup index of its first.
std::uint32_t push_vertices(const Context& ctx, const Attributes& a, const Placement& pl,
                            Soup& soup) {
  const std::size_t base = open_vertices(ctx, a, a.positions.size(), soup);
  parallel_chunks(a.positions.size(), [&](std::size_t first, std::size_t end) {
    for (std::size_t v = first; v < end; ++v) place_vertex(a, v, pl, base + v, soup);
  });
  return static_cast<std::uint32_t>(base);
}

// t, its winding reversed where the placement mirrors.
glm::uvec3 oriented(glm::uvec3 t, bool flip) {
  return flip ? glm::uvec3(t.x, t.z, t.y) : t;
}

// Appends the triangles `local` (over vertices from `base`), on all cores.
void push_triangles(const std::vector<glm::uvec3>& local, std::uint32_t base, bool flip,
                    std::uint32_t material, Soup& soup) {
  const std::size_t at = soup.triangles.size();
  soup.triangles.resize(at + local.size());
  soup.triangle_material.resize(at + local.size(), material);
  parallel_chunks(local.size(), [&](std::size_t first, std::size_t end) {
    for (std::size_t k = first; k < end; ++k) {
      soup.triangles[at + k] = oriented(local[k] + base, flip);
    }
  });
}

void push_triangle(glm::uvec3 t, bool flip, std::uint32_t material, Soup& soup) {
  soup.triangles.push_back(oriented(t, flip));
  soup.triangle_material.push_back(material);
}

} // namespace

namespace {

// Capacity for n elements: the first time the scene's hint (at least n), else at least 1.5 x the
// capacity (a hint that fell short still grows geometrically).
template <class T>
void grow(std::vector<T>& v, std::size_t n, std::size_t hint) {
  if (n <= v.capacity()) return;
  reserve_huge(v, v.capacity() == 0 ? std::max(n, hint)
                                    : std::max(n, v.capacity() + v.capacity() / 2));
}

// Room for `vertices` more vertices and `triangles` more triangles.
void reserve(Soup& soup, std::size_t vertices, std::size_t triangles, const Attributes& a) {
  const std::size_t n = soup.positions.size() + vertices, h = soup.vertex_hint;
  // One position more than the hint: room for the ray tracer's read past the last one
  // (finish_geometry), so that the positions are not copied to make it.
  grow(soup.positions, n, h + 1);
  grow(soup.normals, n, h);
  if (!a.uvs.empty() || !soup.uvs.empty()) grow(soup.uvs, n, h);
  if (!a.uvs1.empty() || !soup.uvs1.empty()) grow(soup.uvs1, n, h);
  if (!a.colors.empty() || !soup.colors.empty()) grow(soup.colors, n, h);
  if (!a.tangents.empty() || !soup.tangents.empty()) grow(soup.tangents, n, h);
  grow(soup.triangles, soup.triangles.size() + triangles, soup.triangle_hint);
  grow(soup.triangle_material, soup.triangle_material.size() + triangles, soup.triangle_hint);
}

Soup::Deform& start_deform(const RawPrimitive& raw, const PrimitivePose& pose, bool skinned,
                           bool flip, Soup& soup) {
  Soup::Deform d;
  d.gltf_node = pose.node;
  if (skinned) {
    d.gltf_joints = pose.skin->joints;
    d.part.joint_matrix = pose.skin->inverse_bind;
  }
  d.part.flat = raw.a.normals.empty();
  d.part.flip = flip;
  d.part.position_targets.resize(raw.targets.positions.size());
  d.part.normal_targets.resize(raw.targets.normals.size());
  d.part.tangent_targets.resize(raw.targets.tangents.size());
  soup.deforms.push_back(std::move(d));
  return soup.deforms.back();
}

// Adds file vertex v, pushed as soup vertex `index`, to the deformed part.
void record(const RawPrimitive& raw, std::size_t v, std::size_t index, Soup::Deform& d) {
  Animation::DeformedPart& p = d.part;
  p.vertices.push_back(std::uint32_t(index));
  p.positions.push_back(raw.a.positions[v]);
  if (!raw.a.normals.empty()) p.normals.push_back(raw.a.normals[v]);
  if (!raw.a.tangents.empty()) p.tangents.push_back(raw.a.tangents[v]);
  for (std::size_t t = 0; t < p.position_targets.size(); ++t)
    p.position_targets[t].push_back(raw.targets.positions[t][v]);
  for (std::size_t t = 0; t < p.normal_targets.size(); ++t)
    p.normal_targets[t].push_back(raw.targets.normals[t][v]);
  for (std::size_t t = 0; t < p.tangent_targets.size(); ++t)
    p.tangent_targets[t].push_back(raw.targets.tangents[t][v]);
  if (!d.gltf_joints.empty()) {
    p.vertex_joints.push_back(raw.influences.joints[v]);
    p.vertex_weights.push_back(raw.influences.weights[v]);
  }
}

// Marks the parts of primitive `pp` (a JSON pointer) that the reader reads as used, so that the
// validator's issues there are reported.
void use_parts(const Context& ctx, const std::string& pp, const json& attrs, UvSets uv,
               const PrimitivePose& pose) {
  ctx.use_exact(pp);
  ctx.use_exact(pp + "/attributes");
  std::vector<std::string> read{"POSITION", "NORMAL", "COLOR_0"};
  for (int set : {uv.slot0, uv.slot1})
    if (set >= 0) read.push_back("TEXCOORD_" + std::to_string(set));
  if (uv.tangent_slot >= 0) read.push_back("TANGENT");
  if (pose.skin) read.insert(read.end(), {"JOINTS_0", "WEIGHTS_0"});
  for (const std::string& name : read)
    if (member(attrs, name.c_str())) ctx.use(pp + "/attributes/" + name);
  for (const char* part : {"/indices", "/mode", "/extensions/KHR_draco_mesh_compression"})
    ctx.use(pp + part);
  if (!pose.morph_weights.empty()) ctx.use(pp + "/targets");
}

} // namespace

void add_size_hint(const Context& ctx, std::uint64_t mesh, Soup& soup) {
  const json& accessors = ctx.array("accessors");
  const auto count = [&](std::optional<std::uint64_t> a) -> std::optional<std::uint64_t> {
    if (!a || *a >= accessors.size()) return std::nullopt;
    return index_member(accessors[std::size_t(*a)], "count");
  };
  const json& meshes = ctx.array("meshes");
  if (mesh >= meshes.size()) return;
  const json* primitives = member(meshes[std::size_t(mesh)], "primitives");
  if (!primitives || !primitives->is_array()) return;
  for (const json& p : *primitives) {
    const json* attrs = member(p, "attributes");
    const auto mode = static_cast<int>(number_member(p, "mode", kTriangles));
    if (!attrs || !attrs->is_object() || mode < kTriangles || mode > 6) continue;
    const auto vertices = count(attribute(*attrs, "POSITION"));
    if (!vertices) continue;
    const std::uint64_t indices = count(index_member(p, "indices")).value_or(*vertices);
    const std::uint64_t triangles =
        std::min(triangle_count(mode, indices), ctx.limits.max_triangles);
    const std::uint64_t placed = attribute(*attrs, "NORMAL") ? *vertices : 3 * triangles;
    const std::uint64_t most = 3 * ctx.limits.max_triangles; // the vertex limit
    soup.vertex_hint = std::size_t(std::min(soup.vertex_hint + std::min(placed, most), most));
    soup.triangle_hint =
        std::size_t(std::min(soup.triangle_hint + triangles, ctx.limits.max_triangles));
  }
}

void append_primitive(const Context& ctx, std::size_t mesh, std::size_t primitive,
                      const PrimitivePose& pose, std::uint32_t material, UvSets uv, Soup& soup) {
  const json& p = ctx.array("meshes")[mesh]["primitives"][primitive];
  const std::string where = element("meshes", mesh) + element(".primitives", primitive);
  const int mode = int(number_member(p, "mode", kTriangles));
  if (mode >= 0 && mode <= 3) {
    ctx.warn("point and line primitives are not supported; skipped");
    return;
  }
  if (mode < kTriangles || mode > 6) ctx.fail(where, "invalid mode " + std::to_string(mode));
  const json* attrs = member(p, "attributes");
  if (!attrs || !attribute(*attrs, "POSITION")) {
    ctx.warn(where + ": a primitive without POSITION draws nothing; skipped");
    return;
  }
  use_parts(ctx, "/meshes/" + std::to_string(mesh) + "/primitives/" + std::to_string(primitive),
            *attrs, uv, pose);
  std::optional<std::vector<std::uint32_t>> draco;
  if (const json* ext = extension(p, "KHR_draco_mesh_compression"))
    draco = decode_draco(ctx, *ext, *attrs, where);
  RawPrimitive raw = read_primitive(ctx, p, pose, uv, where);
  std::vector<glm::uvec3> local = read_triangles(
      ctx, p, mode, std::move(draco), raw.a.positions.size(), soup.triangles.size(), where);
  if (uv.tangent_slot >= 0 && raw.a.tangents.empty())
    generate_tangents(raw, uv.tangent_slot, local);
  const bool skinned = pose.skin && !raw.influences.joints.empty();
  const bool deformed = skinned || !raw.targets.positions.empty();
  // The file's attributes are kept beside the posed ones only when an animation needs them.
  const Attributes a = deformed ? posed_attributes(raw, pose) : std::move(raw.a);
  const Placement pl = placement(skinned ? glm::dmat4(1.0) : pose.world);
  local = drop_non_finite(std::move(local), a, pl, where, soup);
  const std::uint64_t vertices = a.normals.empty() ? 3 * local.size() : a.positions.size();
  if (soup.positions.size() + vertices > 3 * ctx.limits.max_triangles) {
    ctx.fail(where, fmt::format("the scene would have {} vertices, over the limit of 3 x {} "
                                "(--max-triangles)",
                                soup.positions.size() + vertices, ctx.limits.max_triangles));
  }
  reserve(soup, std::size_t(vertices), local.size(), a);
  soup.has_uvs = soup.has_uvs || !a.uvs.empty();
  soup.has_uvs1 = soup.has_uvs1 || !a.uvs1.empty();
  soup.has_colors = soup.has_colors || !a.colors.empty();
  soup.has_tangents = soup.has_tangents || !a.tangents.empty();
  Soup::Deform* deform = nullptr;
  if (soup.record_deforms && deformed)
    deform = &start_deform(raw, pose, skinned, a.normals.empty() && pl.flip, soup);
  if (!a.normals.empty()) {
    const std::uint32_t base = push_vertices(ctx, a, pl, soup);
    if (deform)
      for (std::size_t v = 0; v < a.positions.size(); ++v) record(raw, v, base + v, *deform);
    push_triangles(local, base, pl.flip, material, soup);
    return;
  }
  for (const glm::uvec3& t : local) { // flat normals: every triangle gets its own vertices
    const glm::uvec3 own{push_vertex(ctx, a, t.x, pl, soup), push_vertex(ctx, a, t.y, pl, soup),
                         push_vertex(ctx, a, t.z, pl, soup)}; // braces: evaluated in order
    if (deform)
      for (int c = 0; c < 3; ++c) record(raw, t[c], own[c], *deform);
    push_triangle(own, pl.flip, material, soup);
  }
}

} // namespace irad::gltf
