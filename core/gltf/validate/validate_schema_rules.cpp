// The schema rules the tables cannot express: dependencies between properties, exactly-one-of,
// asset versions, camera planes, and the extension objects' cross-property rules. Each rule
// receives a JSON object already checked against its table (types may still be wrong: every
// access is type-tested).
#include "core/gltf/validate/validate_schema_internal.h"

#include <algorithm>
#include <numbers>
#include <set>

namespace irad::gltf::schema {
namespace {

bool has(const nlohmann::json& obj, std::string_view key) {
  return member(obj, key) != nullptr;
}

bool string_is(const nlohmann::json& obj, std::string_view key, std::string_view value) {
  const nlohmann::json* v = member(obj, key);
  return v != nullptr && v->is_string() && v->get_ref<const std::string&>() == value;
}

void depends(const nlohmann::json& obj, std::string_view key, std::string_view needed,
             const std::string& ptr, Ctx& ctx) {
  if (has(obj, key) && !has(obj, needed))
    ctx.add(child(ptr, key), "UNSATISFIED_DEPENDENCY",
            "needs '" + std::string(needed) + "' to be defined");
}

// "major.minor" as two numbers (saturated); false when the string has another form.
bool parse_version(const nlohmann::json* v, std::uint64_t& major, std::uint64_t& minor) {
  if (v == nullptr || !v->is_string()) return false;
  const auto& s = v->get_ref<const std::string&>();
  const std::size_t dot = s.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == s.size()) return false;
  std::uint64_t* out = &major;
  major = minor = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (i == dot) {
      out = &minor;
      continue;
    }
    if (s[i] < '0' || s[i] > '9') return false;
    *out = std::min<std::uint64_t>(*out * 10 + static_cast<std::uint64_t>(s[i] - '0'), 1u << 30);
  }
  return true;
}

std::size_t components(const std::string& type) {
  constexpr std::array<std::pair<std::string_view, std::size_t>, 7> table{{{"SCALAR", 1},
                                                                           {"VEC2", 2},
                                                                           {"VEC3", 3},
                                                                           {"VEC4", 4},
                                                                           {"MAT2", 4},
                                                                           {"MAT3", 9},
                                                                           {"MAT4", 16}}};
  for (const auto& [name, n] : table)
    if (name == type) return n;
  return 0;
}

} // namespace

void rule_root(const nlohmann::json& obj, const std::string&, Ctx& ctx) {
  depends(obj, "extensionsRequired", "extensionsUsed", "", ctx);
  const nlohmann::json* required = member(obj, "extensionsRequired");
  if (required != nullptr && required->is_array())
    for (std::size_t i = 0; i < required->size(); ++i) {
      const nlohmann::json& e = (*required)[i];
      if (e.is_string() && !ctx.used(e.get_ref<const std::string&>()))
        ctx.add(child("/extensionsRequired", i), "UNUSED_EXTENSION_REQUIRED",
                "a required extension must also be in extensionsUsed");
    }
  const nlohmann::json* used = member(obj, "extensionsUsed");
  if (used == nullptr || !used->is_array()) return;
  for (std::size_t i = 0; i < used->size(); ++i) {
    if ((*used)[i] != "KHR_mesh_quantization") continue;
    const bool listed =
        required != nullptr && required->is_array() &&
        std::find(required->begin(), required->end(), (*used)[i]) != required->end();
    if (!listed)
      ctx.add(child("/extensionsUsed", i), "NON_REQUIRED_EXTENSION",
              "this extension must also be in extensionsRequired");
  }
}

void rule_asset(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx) {
  std::uint64_t major = 0, minor = 0, min_major = 0, min_minor = 0;
  if (!parse_version(member(obj, "version"), major, minor)) return;
  if (major != 2)
    ctx.add(child(ptr, "version"), "UNKNOWN_ASSET_MAJOR_VERSION",
            "glTF major version " + std::to_string(major) + " is not supported");
  if (parse_version(member(obj, "minVersion"), min_major, min_minor) &&
      (min_major > major || (min_major == major && min_minor > minor)))
    ctx.add(child(ptr, "minVersion"), "ASSET_MIN_VERSION_GREATER_THAN_VERSION",
            "minVersion is later than version");
}

void rule_accessor(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx) {
  depends(obj, "byteOffset", "bufferView", ptr, ctx);
  const nlohmann::json* type = member(obj, "type");
  if (type == nullptr || !type->is_string()) return;
  const std::size_t n = components(type->get_ref<const std::string&>());
  if (n == 0) return;
  for (std::string_view key : {"min", "max"}) {
    const nlohmann::json* v = member(obj, key);
    if (v != nullptr && v->is_array() && !v->empty() && v->size() <= 16 && v->size() != n)
      ctx.add(child(ptr, key), "ARRAY_LENGTH_NOT_IN_LIST",
              "needs " + std::to_string(n) + " elements for this accessor type");
  }
}

void rule_camera(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx) {
  if (has(obj, "orthographic") && has(obj, "perspective"))
    return ctx.add(ptr, "ONE_OF_MISMATCH",
                   "only one of 'orthographic' and 'perspective' may be defined");
  for (std::string_view type : {"orthographic", "perspective"})
    if (string_is(obj, "type", type) && !has(obj, type))
      ctx.add(ptr, "UNDEFINED_PROPERTY", "property '" + std::string(type) + "' is missing");
}

void rule_orthographic(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx) {
  for (std::string_view key : {"xmag", "ymag"}) {
    double mag = 1.0;
    if (number_of(obj, key, mag) && mag == 0.0)
      ctx.add(child(ptr, key), "CAMERA_XMAG_YMAG_ZERO", "xmag and ymag must be non-zero");
  }
  double zfar = 0.0, znear = 0.0;
  if (number_of(obj, "zfar", zfar) && number_of(obj, "znear", znear) && zfar <= znear)
    ctx.add(ptr, "CAMERA_ZFAR_LEQUAL_ZNEAR", "zfar is not beyond znear");
}

void rule_perspective(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx) {
  double zfar = 0.0, znear = 0.0;
  if (number_of(obj, "zfar", zfar) && number_of(obj, "znear", znear) && zfar <= znear)
    ctx.add(ptr, "CAMERA_ZFAR_LEQUAL_ZNEAR", "zfar is not beyond znear");
}

void rule_node(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx) {
  depends(obj, "skin", "mesh", ptr, ctx);
  depends(obj, "weights", "mesh", ptr, ctx);
}

void rule_channel_target(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx) {
  const nlohmann::json* ext = member(obj, "extensions");
  if (ext == nullptr || !has(*ext, "KHR_animation_pointer")) return;
  const std::string at = child(child(ptr, "extensions"), "KHR_animation_pointer");
  if (has(obj, "node"))
    ctx.add(at, "KHR_ANIMATION_POINTER_ANIMATION_CHANNEL_TARGET_NODE",
            "a pointer target must not also name a node");
  if (!string_is(obj, "path", "pointer"))
    ctx.add(at, "KHR_ANIMATION_POINTER_ANIMATION_CHANNEL_TARGET_PATH",
            "a pointer target needs path 'pointer'");
}

void rule_light(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx) {
  const nlohmann::json* spot = member(obj, "spot");
  if (string_is(obj, "type", "spot") && spot == nullptr)
    return ctx.add(ptr, "UNDEFINED_PROPERTY", "property 'spot' is missing");
  if (spot == nullptr || !spot->is_object()) return;
  double inner = 0.0, outer = std::numbers::pi / 4.0;
  number_of(*spot, "innerConeAngle", inner);
  number_of(*spot, "outerConeAngle", outer);
  if (outer <= inner)
    ctx.add(child(child(ptr, "spot"), "outerConeAngle"), "KHR_LIGHTS_PUNCTUAL_LIGHT_SPOT_ANGLES",
            "outerConeAngle must exceed innerConeAngle");
}

void rule_node_light(const nlohmann::json&, const std::string& ptr, Ctx& ctx) {
  const nlohmann::json* ext = member(ctx.root, "extensions");
  if (ext == nullptr || !has(*ext, "KHR_lights_punctual"))
    ctx.add(ptr, "UNSATISFIED_DEPENDENCY", "needs the document's KHR_lights_punctual object");
}

void rule_primitive_variants(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx) {
  const nlohmann::json* mappings = member(obj, "mappings");
  if (mappings == nullptr || !mappings->is_array()) return;
  const nlohmann::json* ext = member(ctx.root, "extensions");
  const bool defined = ext != nullptr && has(*ext, "KHR_materials_variants");
  std::set<nlohmann::json> seen; // the variants of the mappings before this one
  for (std::size_t i = 0; i < mappings->size(); ++i) {
    const std::string at = child(child(ptr, "mappings"), i);
    if (!defined)
      ctx.add(at, "UNSATISFIED_DEPENDENCY", "needs the document's KHR_materials_variants object");
    const nlohmann::json* variants = member((*mappings)[i], "variants");
    if (variants == nullptr || !variants->is_array()) continue;
    for (std::size_t j = 0; j < variants->size(); ++j)
      if ((*variants)[j].is_number_integer() && seen.count((*variants)[j]) != 0)
        ctx.add(child(child(at, "variants"), j), "KHR_MATERIALS_VARIANTS_NON_UNIQUE_VARIANT",
                "this variant is already mapped for this primitive");
    for (const nlohmann::json& v : *variants)
      if (v.is_number_integer()) seen.insert(v); // numbers only: no NaN in the ordering
  }
}

void rule_ior(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx) {
  double ior = 1.5;
  if (number_of(obj, "ior", ior) && ior > 0.0 && ior < 1.0)
    ctx.add(child(ptr, "ior"), "VALUE_NOT_IN_RANGE", "ior must be 0 or at least 1");
}

} // namespace irad::gltf::schema
