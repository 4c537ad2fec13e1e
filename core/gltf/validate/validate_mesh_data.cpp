// The data of mesh primitives' accessors: index ranges, unit normals and tangents, clamped
// colours, joint indices within the skin, non-negative weights that sum to one.
#include "core/gltf/validate/validate_semantics_read.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <span>

namespace irad::gltf::sem {

using nlohmann::json;

namespace {

// Tolerance on a unit length or a sum of one, by component type: the quantisation of normalised
// integers makes them coarser than floats.
double tolerance(std::int64_t component_type) {
  switch (component_type) {
  case kByte:
  case kUnsignedByte:
    return 0.02;
  case kShort:
  case kUnsignedShort:
    return 0.001;
  default:
    return 0.0005;
  }
}

void check_indices_data(const Context& ctx, std::int64_t acc, std::int64_t vertices,
                        const std::string& ptr) {
  const auto a = accessor_view(ctx, acc);
  if (!a || !a->valid || a->type != "SCALAR") return;
  double restart = 0;
  if (a->component_type == kUnsignedByte)
    restart = 255;
  else if (a->component_type == kUnsignedShort)
    restart = 65535;
  else if (a->component_type == kUnsignedInt)
    restart = 4294967295.0;
  else
    return;
  bool oob = false, restarted = false;
  const bool read = stream_accessor(ctx, acc, [&](std::span<const double> values, std::int64_t) {
    for (double v : values) {
      if (v == restart)
        restarted = true;
      else if (vertices >= 0 && v >= static_cast<double>(vertices))
        oob = true;
    }
  });
  if (!read) return;
  if (restarted)
    ctx.add(ptr, "ACCESSOR_INDEX_PRIMITIVE_RESTART", "an index is the primitive restart value");
  if (oob) ctx.add(ptr, "ACCESSOR_INDEX_OOB", "an index is not less than the number of vertices");
}

// NORMAL (vec3) and TANGENT (xyz, and w = ±1) must be unit vectors.
void check_unit(const Context& ctx, std::int64_t acc, bool tangent, const std::string& ptr) {
  const auto a = accessor_view(ctx, acc);
  if (!a || !a->valid || a->components != (tangent ? 4 : 3)) return;
  const auto n = static_cast<std::size_t>(a->components);
  const double tol = tolerance(a->component_type);
  bool non_unit = false, bad_sign = false;
  const bool read = stream_accessor(ctx, acc, [&](std::span<const double> values, std::int64_t) {
    for (std::size_t e = 0; e + n <= values.size(); e += n) {
      double len2 = 0;
      for (std::size_t c = 0; c < 3; ++c) {
        const double v = normalize(values[e + c], a->component_type, a->normalized);
        len2 += v * v;
      }
      if (std::isfinite(len2) && std::fabs(std::sqrt(len2) - 1.0) > tol) non_unit = true;
      if (tangent) {
        const double w = normalize(values[e + 3], a->component_type, a->normalized);
        if (std::fabs(std::fabs(w) - 1.0) > tol) bad_sign = true;
      }
    }
  });
  if (!read) return;
  if (non_unit) ctx.add(ptr, "ACCESSOR_VECTOR3_NON_UNIT", "a vector is not of unit length");
  if (bad_sign) ctx.add(ptr, "ACCESSOR_INVALID_SIGN", "a tangent's w is not 1 or -1");
}

void check_color(const Context& ctx, std::int64_t acc, const std::string& ptr) {
  const auto a = accessor_view(ctx, acc);
  if (!a || !a->valid || a->component_type != kFloat) return;
  bool clamped = true;
  const bool read = stream_accessor(ctx, acc, [&](std::span<const double> values, std::int64_t) {
    for (double v : values)
      if (!(v >= 0.0 && v <= 1.0) && std::isfinite(v)) clamped = false; // NaN: INVALID_FLOAT
  });
  if (read && !clamped) ctx.add(ptr, "ACCESSOR_NON_CLAMPED", "a colour component is outside 0..1");
}

// Per mesh, the fewest joints among the skins nodes apply to it (meshes no node skins: absent).
std::map<std::int64_t, std::int64_t> joint_limits(const Context& ctx) {
  std::map<std::int64_t, std::int64_t> limits;
  for (const json& node : ctx.list("nodes")) {
    const auto m = index(node, "mesh");
    const auto s = index(node, "skin");
    const json* skin = s ? ctx.object("skins", *s) : nullptr;
    if (!m || skin == nullptr || !has(*skin, "joints")) continue;
    const auto n = static_cast<std::int64_t>(array_size(*skin, "joints"));
    auto [it, inserted] = limits.emplace(*m, n);
    if (!inserted) it->second = std::min(it->second, n);
  }
  return limits;
}

struct SkinSets {
  std::map<int, std::pair<std::int64_t, std::string>> joints, weights; // set → accessor, pointer
};

// A vertex's weights over all sets: a joint out of the skin or used twice (with a non-zero
// weight) does not count, nor does a negative weight. Reports a duplicate joint at its JOINTS_n.
void sum_weights(const Context& ctx, const SkinSets& sets, std::optional<std::int64_t> limit,
                 std::vector<double>& sums) {
  std::vector<std::pair<AccessorData, std::string>> joints;
  for (const auto& [set, jp] : sets.joints)
    joints.emplace_back(read_accessor(ctx, jp.first), jp.second);
  std::vector<std::pair<AccessorData, AccessorView>> weights;
  for (const auto& [set, wp] : sets.weights) {
    const auto a = accessor_view(ctx, wp.first);
    weights.emplace_back(read_accessor(ctx, wp.first), a.value_or(AccessorView{}));
  }
  const bool joints_ok = joints.size() == weights.size() &&
                         std::all_of(joints.begin(), joints.end(), [&](const auto& j) {
                           return j.first.ok && j.first.values.size() == sums.size() * 4;
                         });
  std::vector<bool> duplicate(joints.size(), false);
  for (std::size_t v = 0; v < sums.size(); ++v) {
    std::vector<double> used;
    for (std::size_t s = 0; s < weights.size(); ++s) {
      for (std::size_t c = 0; c < 4; ++c) {
        const AccessorView& a = weights[s].second;
        const double w =
            normalize(weights[s].first.values[v * 4 + c], a.component_type, a.normalized);
        if (!joints_ok) {
          sums[v] += w;
          continue;
        }
        const double j = joints[s].first.values[v * 4 + c];
        if (limit && j >= static_cast<double>(*limit)) continue;
        if (w != 0 && std::find(used.begin(), used.end(), j) != used.end()) {
          duplicate[s] = true;
          continue;
        }
        if (w < 0) continue;
        if (w != 0) used.push_back(j);
        sums[v] += w;
      }
    }
  }
  for (std::size_t s = 0; s < duplicate.size(); ++s)
    if (duplicate[s])
      ctx.add(joints[s].second, "ACCESSOR_JOINTS_INDEX_DUPLICATE",
              "a vertex uses the same joint twice");
}

void check_skin_data(const Context& ctx, const SkinSets& sets, std::optional<std::int64_t> limit) {
  for (const auto& [set, jp] : sets.joints) {
    if (!limit) break;
    const AccessorData d = read_accessor(ctx, jp.first);
    if (!d.ok) continue;
    for (double v : d.values) {
      if (v < static_cast<double>(*limit)) continue;
      ctx.add(jp.second, "ACCESSOR_JOINTS_INDEX_OOB", "a joint index is not in the skin");
      break;
    }
  }
  std::size_t vertices = 0;
  bool all_read = true;
  for (const auto& [set, wp] : sets.weights) {
    const auto a = accessor_view(ctx, wp.first);
    const AccessorData d = read_accessor(ctx, wp.first);
    if (!a || !d.ok || a->components != 4 || (vertices != 0 && d.values.size() != vertices * 4)) {
      all_read = false;
      continue;
    }
    vertices = d.values.size() / 4;
    for (double raw : d.values) {
      if (normalize(raw, a->component_type, a->normalized) >= 0) continue;
      ctx.add(wp.second, "ACCESSOR_WEIGHTS_NEGATIVE", "a joint weight is negative");
      break;
    }
  }
  if (!all_read || sets.weights.empty()) return;
  std::vector<double> sums(vertices, 0.0);
  sum_weights(ctx, sets, limit, sums);
  const double tol = 0.002 * static_cast<double>(sets.weights.size());
  for (double s : sums) {
    if (!std::isfinite(s) || std::fabs(s - 1.0) <= tol || s == 0.0) continue;
    for (const auto& [set, wp] : sets.weights)
      ctx.add(wp.second, "ACCESSOR_WEIGHTS_NON_NORMALIZED", "a vertex's weights do not sum to 1");
    return;
  }
}

// `checked`: accessors whose NORMAL, TANGENT or COLOR data was checked already (the validator
// checks an accessor's data once, under its first semantic).
void check_primitive(const Context& ctx, const json& prim, std::optional<std::int64_t> joints,
                     const std::string& ptr, std::set<std::int64_t>& checked) {
  const json* attrs = member(prim, "attributes");
  if (attrs == nullptr || !attrs->is_object()) return;
  std::int64_t vertices = -1;
  SkinSets sets;
  for (const auto& [name, acc] : attrs->items()) {
    const auto ai = as_int(&acc);
    if (!ai || ctx.object("accessors", *ai) == nullptr) continue;
    const std::string p = at(at(ptr, "attributes"), name);
    if (const auto a = accessor_view(ctx, *ai);
        a && a->valid && (vertices < 0 || name == "POSITION"))
      vertices = a->count;
    const bool vector = name == "NORMAL" || name == "TANGENT" || name.rfind("COLOR_", 0) == 0;
    if (vector && checked.insert(*ai).second) {
      if (name == "NORMAL") check_unit(ctx, *ai, false, p);
      if (name == "TANGENT") check_unit(ctx, *ai, true, p);
      if (name.rfind("COLOR_", 0) == 0) check_color(ctx, *ai, p);
    }
    if (name.rfind("JOINTS_", 0) == 0) sets.joints[std::atoi(name.c_str() + 7)] = {*ai, p};
    if (name.rfind("WEIGHTS_", 0) == 0) sets.weights[std::atoi(name.c_str() + 8)] = {*ai, p};
  }
  if (const auto ind = index(prim, "indices"); ind && ctx.object("accessors", *ind))
    check_indices_data(ctx, *ind, vertices, at(ptr, "indices"));
  if (!sets.joints.empty() || !sets.weights.empty()) check_skin_data(ctx, sets, joints);
}

} // namespace

void check_mesh_data(const Context& ctx) {
  std::set<std::int64_t> checked;
  const auto limits = joint_limits(ctx);
  const json& meshes = ctx.list("meshes");
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const json* prims = member(meshes[m], "primitives");
    if (prims == nullptr || !prims->is_array()) continue;
    for (std::size_t p = 0; p < prims->size(); ++p) {
      const json* ext = member((*prims)[p], "extensions");
      if (ext != nullptr && has(*ext, "KHR_draco_mesh_compression")) continue;
      const auto mi = static_cast<std::int64_t>(m);
      const auto limit = limits.find(mi);
      check_primitive(
          ctx, (*prims)[p], limit != limits.end() ? std::optional(limit->second) : std::nullopt,
          at(at(at("/meshes", mi), "primitives"), static_cast<std::int64_t>(p)), checked);
    }
  }
}

} // namespace irad::gltf::sem
