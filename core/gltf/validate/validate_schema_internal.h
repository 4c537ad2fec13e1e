#pragma once
// Internal to core/gltf/validate_schema*.cpp: the glTF 2.0 JSON schema (and the JSON schemas of
// the extensions irad knows) as const tables, and the walker's context. A Schema describes one
// object type: its properties (JSON type, required, numeric bounds, array lengths and
// uniqueness, the array an index refers to, where its extensions may be) and an optional rule for
// what the tables cannot say (dependencies, exactly-one-of, camera planes, URIs). Pointers and
// codes are the validator's; messages are irad's.
#include "core/gltf/validate/validate_parts.h"

#include <climits>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>

namespace irad::gltf::schema {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

enum class Kind : std::uint8_t {
  Any,     // not checked (extras)
  Bool,    // JSON boolean
  Number,  // finite JSON number, within [min, max] (exclusive where min_excl / max_excl)
  Integer, // JSON number with a whole value (1.0 too), within bounds, a multiple_of
  String,  // JSON string, matching `pattern` when given
  Index,   // non-negative integer < the size of the array named by `target`
  Object,  // JSON object checked against `object`
  Array,   // JSON array of `item` elements, min_items..max_items long, unique when asked
};

struct Schema;
struct Ctx;

// Special patterns (the schema's regular expressions, decided by hand-written matchers).
enum class Pattern : std::uint8_t { None, Version, JsonPointer };

// One property of an object type; for Kind::Array the element constraints live here too
// (bounds, target and object apply to each element). Enumerations are not listed: the
// validator reports a value outside one as a warning (VALUE_NOT_IN_LIST), not an error.
struct Prop {
  std::string_view name;
  Kind kind = Kind::Any;
  bool required = false;
  double min = -kInf;
  double max = kInf;
  bool min_excl = false;
  bool max_excl = false;
  // Index: a JSON pointer into the document ("/accessors"), or "@samplers" for the samplers of
  // the enclosing animation.
  std::string_view target = {};
  const Schema* object = nullptr;
  Kind item = Kind::Any;
  int min_items = 0;
  int max_items = INT_MAX;
  bool unique = false;
  Pattern pattern = Pattern::None;
  std::int64_t multiple_of = 0;
  // Array of objects at the document's top level: a non-object element is a TYPE_MISMATCH at
  // the element (nested arrays report ARRAY_TYPE_MISMATCH at the array, as the validator does).
  bool collection = false;
};

// Extra checks of one object that the tables do not express; `obj` is a JSON object.
using Rule = void (*)(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);

struct Schema {
  // Where extension objects found here are: "root", "node", "material", "textureInfo", ...
  std::string_view location = {};
  std::span<const Prop> props = {};
  Rule rule = nullptr;
  // When set, every member other than extensions/extras is checked as this property
  // (mesh attributes, morph targets); min_members: fewer is EMPTY_ENTITY.
  const Prop* each = nullptr;
  int min_members = 0;
  // Set for the animation: its `samplers` are what "@samplers" indices inside it refer to.
  bool scopes_samplers = false;
};

// An extension irad's validator knows: where it may appear and the schema of its object there.
struct Extension {
  std::string_view name;
  std::string_view location; // "" where it never has objects (KHR_mesh_quantization)
  const Schema* schema;      // nullptr: accepted without checks
};

struct Ctx {
  const nlohmann::json& root;
  std::vector<Issue>& issues;
  const nlohmann::json* samplers = nullptr; // of the animation being checked
  void add(std::string pointer, std::string_view code, std::string message) const {
    issues.push_back({std::move(pointer), std::string(code), std::move(message)});
  }
  bool used(std::string_view extension) const; // listed in extensionsUsed
};

// Tables (validate_schema_tables.cpp, validate_schema_ext_tables.cpp).
extern const Schema kRoot;
extern const Schema kTextureInfo;       // textureInfo
extern const Schema kNormalTextureInfo; // material.normalTextureInfo
std::span<const Extension> extensions();

// Building blocks of both tables: a number in [0, 1], a textureInfo object, an index into the
// document's array at `target`.
constexpr Prop unit(std::string_view name) {
  return {.name = name, .kind = Kind::Number, .min = 0.0, .max = 1.0};
}
constexpr Prop texture(std::string_view name) {
  return {.name = name, .kind = Kind::Object, .object = &kTextureInfo};
}
constexpr Prop index(std::string_view name, std::string_view target, bool required = false) {
  return {.name = name, .kind = Kind::Index, .required = required, .target = target};
}

// Walker (validate_schema.cpp).
std::string child(const std::string& ptr, std::string_view key);
std::string child(const std::string& ptr, std::size_t index);
void check_object(const nlohmann::json& obj, const Schema& s, const std::string& ptr, Ctx& ctx);
// Number of a JSON value when it is one (integers too); nullptr-safe lookups.
bool number_of(const nlohmann::json& obj, std::string_view key, double& out);
const nlohmann::json* member(const nlohmann::json& obj, std::string_view key);

// Rules (validate_schema_rules.cpp, validate_schema_uri.cpp).
void rule_root(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);
void rule_asset(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);
void rule_accessor(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);
void rule_camera(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);
void rule_orthographic(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);
void rule_perspective(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);
void rule_node(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);
void rule_channel_target(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);
void rule_light(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);
void rule_node_light(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);
void rule_primitive_variants(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);
void rule_ior(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);
void rule_buffer(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);
void rule_image(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);
void rule_texture(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx);

} // namespace irad::gltf::schema
