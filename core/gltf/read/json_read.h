#pragma once
// Internal to the glTF loader: reading values out of the glTF JSON defensively (any property may
// hold any JSON type in a broken file), and the two spellings of an element: the JSON pointer
// "/meshes/2/primitives/0" (the validator's) and the path "meshes[2].primitives[0]" (irad's
// messages).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace irad::gltf {

using json = nlohmann::json;

// The member `key` of `object`, or nullptr when object is not an object or lacks it.
inline const json* member(const json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

// A JSON number that is a non-negative integer (1.0 counts: JSON does not distinguish it).
inline std::optional<std::uint64_t> as_index(const json& value) {
  if (value.is_number_unsigned()) return value.get<std::uint64_t>();
  if (value.is_number_integer()) return std::nullopt; // negative
  if (value.is_number_float()) {
    const double d = value.get<double>();
    if (d >= 0.0 && d < 9.007199254740992e15 && d == std::floor(d)) return std::uint64_t(d);
  }
  return std::nullopt;
}

// member `key` as a non-negative integer; nullopt when absent or not one.
inline std::optional<std::uint64_t> index_member(const json& object, const char* key) {
  const json* v = member(object, key);
  return v ? as_index(*v) : std::nullopt;
}

// member `key` as a number, `fallback` when absent or not a number.
inline double number_member(const json& object, const char* key, double fallback) {
  const json* v = member(object, key);
  return v && v->is_number() ? v->get<double>() : fallback;
}

inline bool bool_member(const json& object, const char* key, bool fallback) {
  const json* v = member(object, key);
  return v && v->is_boolean() ? v->get<bool>() : fallback;
}

inline std::string string_member(const json& object, const char* key,
                                 const std::string& fallback = {}) {
  const json* v = member(object, key);
  return v && v->is_string() ? v->get<std::string>() : fallback;
}

// member `key` as an array of numbers; empty when absent, not an array, or holding a non-number.
inline std::vector<double> numbers_member(const json& object, const char* key) {
  const json* v = member(object, key);
  std::vector<double> out;
  if (!v || !v->is_array()) return out;
  for (const json& x : *v) {
    if (!x.is_number()) return {};
    out.push_back(x.get<double>());
  }
  return out;
}

// The top-level array `name` of the document, or an empty array.
inline const json& root_array(const json& root, const char* name) {
  static const json kEmpty = json::array();
  const json* v = member(root, name);
  return v && v->is_array() ? *v : kEmpty;
}

// The extension object `name` of element `object`, or nullptr.
inline const json* extension(const json& object, const char* name) {
  const json* ext = member(object, "extensions");
  return ext ? member(*ext, name) : nullptr;
}

// "/meshes/2/primitives/0/attributes/NORMAL" -> "meshes[2].primitives[0].attributes.NORMAL"
// (segments of digits become [n]; ~1 and ~0 are unescaped).
inline std::string path_of(const std::string& pointer) {
  std::string out;
  std::size_t at = pointer.empty() || pointer[0] != '/' ? 0 : 1;
  while (at <= pointer.size() && !pointer.empty()) {
    const std::size_t end = std::min(pointer.find('/', at), pointer.size());
    std::string part;
    for (std::size_t k = at; k < end; ++k) {
      const bool escape = pointer[k] == '~' && k + 1 < end;
      part += escape ? (pointer[k + 1] == '1' ? '/' : '~') : pointer[k];
      k += escape ? 1 : 0;
    }
    const bool digits = !part.empty() && part.find_first_not_of("0123456789") == std::string::npos;
    if (digits && !out.empty())
      out += "[" + part + "]";
    else
      out += (out.empty() ? "" : ".") + part;
    if (end == pointer.size()) break;
    at = end + 1;
  }
  return out;
}

// A JSON pointer segment (RFC 6901): '~' as "~0", '/' as "~1".
inline std::string pointer_escape(std::string_view segment) {
  std::string out;
  for (char c : segment) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return out;
}

// "/array/i" and "/array/i/sub".
inline std::string pointer_of(const char* array, std::size_t i) {
  return std::string("/") + array + "/" + std::to_string(i);
}

} // namespace irad::gltf
