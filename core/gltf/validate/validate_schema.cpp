// check_schema: walks the document against the tables of validate_schema_tables.cpp and
// validate_schema_ext_tables.cpp. Every access is guarded by a type test, so no JSON value
// makes it throw.
#include "core/gltf/validate/validate_schema_internal.h"

#include "core/gltf/read/json_read.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>

namespace irad::gltf::schema {
namespace {

// The value's name in messages: its JSON type.
std::string_view type_name(const nlohmann::json& v) {
  return v.type_name();
}

void type_mismatch(const nlohmann::json& v, std::string_view expected, const std::string& ptr,
                   Ctx& ctx) {
  ctx.add(ptr, "TYPE_MISMATCH",
          "expected " + std::string(expected) + ", found " + std::string(type_name(v)));
}

// JSON integers, and numbers written with a fraction or exponent whose value is whole (1.0,
// 10e-1), as the validator accepts them; `out` saturates to the int64 range.
bool integer_of(const nlohmann::json& v, std::int64_t& out) {
  if (v.is_number_unsigned()) {
    out = static_cast<std::int64_t>(std::min<std::uint64_t>(v.get<std::uint64_t>(), INT64_MAX));
    return true;
  }
  if (v.is_number_integer()) {
    out = v.get<std::int64_t>();
    return true;
  }
  if (!v.is_number_float()) return false;
  const double x = v.get<double>();
  if (!std::isfinite(x) || x != std::floor(x)) return false;
  out = x >= 9.2e18 ? INT64_MAX : x <= -9.2e18 ? INT64_MIN : static_cast<std::int64_t>(x);
  return true;
}

// The size of the array `target` names; nullopt when the object that should hold it is absent
// (an extension's document-level object: its absence is reported as a dependency instead).
std::optional<std::size_t> target_size(std::string_view target, const Ctx& ctx) {
  if (target == "@samplers")
    return ctx.samplers != nullptr && ctx.samplers->is_array() ? ctx.samplers->size() : 0;
  const nlohmann::json* at = &ctx.root;
  const bool in_extension = target.starts_with("/extensions/");
  std::size_t depth = 0;
  while (!target.empty()) {
    target.remove_prefix(1);
    const std::size_t end = std::min(target.find('/'), target.size());
    const nlohmann::json* next = member(*at, target.substr(0, end));
    target.remove_prefix(end);
    ++depth;
    if (next == nullptr) {
      if (in_extension && depth <= 2) return std::nullopt;
      return 0;
    }
    at = next;
  }
  return at->is_array() ? at->size() : 0;
}

bool in_bounds(double x, const Prop& p) {
  if (p.min_excl ? !(x > p.min) : !(x >= p.min)) return false;
  return p.max_excl ? x < p.max : x <= p.max;
}

void out_of_range(const nlohmann::json& v, const std::string& ptr, Ctx& ctx) {
  ctx.add(ptr, "VALUE_NOT_IN_RANGE", "value " + v.dump() + " is out of range");
}

void invalid_index(const std::string& ptr, Ctx& ctx) {
  ctx.add(ptr, "INVALID_INDEX", "an index must be a non-negative integer");
}

bool pattern_matches(std::string_view s, Pattern pattern) {
  if (pattern == Pattern::Version) {
    const std::size_t dot = s.find('.');
    auto digits = [](std::string_view d) {
      return !d.empty() &&
             std::all_of(d.begin(), d.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    return dot != std::string_view::npos && digits(s.substr(0, dot)) && digits(s.substr(dot + 1));
  }
  if (pattern == Pattern::JsonPointer) {
    if (!s.empty() && s.front() != '/') return false;
    for (std::size_t i = 0; i < s.size(); ++i)
      if (s[i] == '~' && (i + 1 >= s.size() || (s[i + 1] != '0' && s[i + 1] != '1'))) return false;
  }
  return true;
}

// A scalar value against the scalar constraints of `p` (kind `kind`); false when its JSON type
// is wrong (nothing reported: the caller decides between TYPE_MISMATCH and ARRAY_TYPE_MISMATCH).
bool check_scalar(const nlohmann::json& v, const Prop& p, Kind kind, const std::string& ptr,
                  Ctx& ctx) {
  switch (kind) {
  case Kind::Any:
    return true;
  case Kind::Bool:
    return v.is_boolean();
  case Kind::Number: {
    if (!v.is_number()) return false;
    const double x = v.get<double>();
    if (!std::isfinite(x) || !in_bounds(x, p)) out_of_range(v, ptr, ctx);
    return true;
  }
  case Kind::Integer: {
    std::int64_t n = 0;
    if (!integer_of(v, n)) return false;
    if (!in_bounds(static_cast<double>(n), p))
      out_of_range(v, ptr, ctx);
    else if (p.multiple_of != 0 && n % p.multiple_of != 0)
      ctx.add(ptr, "VALUE_MULTIPLE_OF",
              "value " + v.dump() + " is not a multiple of " + std::to_string(p.multiple_of));
    return true;
  }
  case Kind::String: {
    if (!v.is_string()) return false;
    const auto& s = v.get_ref<const std::string&>();
    if (!pattern_matches(s, p.pattern))
      ctx.add(ptr, "PATTERN_MISMATCH", "value '" + s + "' does not have the required form");
    return true;
  }
  case Kind::Index: {
    std::int64_t n = 0;
    if (!integer_of(v, n)) return false;
    if (n < 0) {
      invalid_index(ptr, ctx);
      return true;
    }
    const std::optional<std::size_t> size = target_size(p.target, ctx);
    if (size && static_cast<std::uint64_t>(n) >= *size)
      ctx.add(ptr, "UNRESOLVED_REFERENCE", "index " + v.dump() + " refers to nothing");
    return true;
  }
  case Kind::Object:
  case Kind::Array:
    return false;
  }
  return false;
}

std::string_view kind_name(Kind k) {
  switch (k) {
  case Kind::Bool:
    return "a boolean";
  case Kind::Number:
    return "a number";
  case Kind::Integer:
  case Kind::Index:
    return "an integer";
  case Kind::String:
    return "a string";
  case Kind::Object:
    return "an object";
  case Kind::Array:
    return "an array";
  case Kind::Any:
    break;
  }
  return "a value";
}

void check_array(const nlohmann::json& v, const Prop& p, const std::string& ptr, Ctx& ctx) {
  if (v.empty() && p.min_items > 0) {
    ctx.add(ptr, "EMPTY_ENTITY", "must not be empty");
    return;
  }
  const auto n = static_cast<std::int64_t>(v.size());
  if (n < p.min_items || n > p.max_items)
    ctx.add(ptr, "ARRAY_LENGTH_NOT_IN_LIST", "has " + std::to_string(n) + " elements");
  bool type_reported = false;
  std::set<nlohmann::json> seen; // for `unique`: O(n log n) on fuzzed, huge arrays
  for (std::size_t i = 0; i < v.size(); ++i) {
    const nlohmann::json& e = v[i];
    const std::string at = child(ptr, i);
    bool ok = true;
    if (p.item == Kind::Object) {
      ok = e.is_object();
      if (ok && p.object != nullptr) check_object(e, *p.object, at, ctx);
      if (!ok && p.collection) {
        type_mismatch(e, "an object", at, ctx);
        continue;
      }
    } else {
      ok = check_scalar(e, p, p.item, at, ctx);
    }
    if (!ok && p.item == Kind::Index) {
      invalid_index(at, ctx); // as the validator: per element, not ARRAY_TYPE_MISMATCH
      continue;
    }
    if (!ok && p.item == Kind::String) {
      ctx.add(at, "ARRAY_TYPE_MISMATCH", "expected a string, found " + std::string(type_name(e)));
      continue;
    }
    if (!ok && !type_reported) {
      ctx.add(ptr, "ARRAY_TYPE_MISMATCH",
              "an element is " + std::string(type_name(e)) + ", not " +
                  std::string(kind_name(p.item)));
      type_reported = true;
    }
    if (ok && p.unique && !seen.insert(e).second)
      ctx.add(at, "DUPLICATE_ELEMENTS", "repeats an earlier element");
  }
}

void check_value(const nlohmann::json& v, const Prop& p, const std::string& ptr, Ctx& ctx) {
  if (p.kind == Kind::Object) {
    if (!v.is_object()) return type_mismatch(v, "an object", ptr, ctx);
    if (p.object != nullptr) check_object(v, *p.object, ptr, ctx);
  } else if (p.kind == Kind::Array) {
    if (!v.is_array()) return type_mismatch(v, "an array", ptr, ctx);
    check_array(v, p, ptr, ctx);
  } else if (!check_scalar(v, p, p.kind, ptr, ctx)) {
    type_mismatch(v, kind_name(p.kind), ptr, ctx);
  }
}

// One extension object found at `location`.
void check_extension(const std::string& name, const nlohmann::json& v, std::string_view location,
                     const std::string& ptr, Ctx& ctx) {
  if (!v.is_object()) type_mismatch(v, "an object", ptr, ctx);
  // As the validator: an extension not in extensionsUsed is not loaded, so nothing more is
  // checked for it.
  if (!ctx.used(name))
    return ctx.add(ptr, "UNDECLARED_EXTENSION",
                   "extension '" + name + "' is not in extensionsUsed");
  if (!v.is_object()) return;
  bool known = false;
  for (const Extension& e : extensions()) {
    if (e.name != name) continue;
    known = true;
    if (e.location != location || location.empty()) continue;
    if (e.schema != nullptr) check_object(v, *e.schema, ptr, ctx);
    return;
  }
  if (known)
    ctx.add(ptr, "UNEXPECTED_EXTENSION_OBJECT", "extension '" + name + "' does not belong here");
}

void check_extensions(const nlohmann::json& v, std::string_view location, const std::string& ptr,
                      Ctx& ctx) {
  if (!v.is_object()) return type_mismatch(v, "an object", ptr, ctx);
  for (auto it = v.begin(); it != v.end(); ++it)
    check_extension(it.key(), it.value(), location, child(ptr, it.key()), ctx);
}

} // namespace

std::string child(const std::string& ptr, std::string_view key) {
  return ptr + '/' + pointer_escape(key);
}

std::string child(const std::string& ptr, std::size_t index) {
  return ptr + '/' + std::to_string(index);
}

const nlohmann::json* member(const nlohmann::json& obj, std::string_view key) {
  if (!obj.is_object()) return nullptr;
  const auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

bool number_of(const nlohmann::json& obj, std::string_view key, double& out) {
  const nlohmann::json* v = member(obj, key);
  if (v == nullptr || !v->is_number()) return false;
  out = v->get<double>();
  return true;
}

bool Ctx::used(std::string_view extension) const {
  const nlohmann::json* list = member(root, "extensionsUsed");
  if (list == nullptr || !list->is_array()) return false;
  return std::any_of(list->begin(), list->end(), [&](const nlohmann::json& e) {
    return e.is_string() && e.get_ref<const std::string&>() == extension;
  });
}

void check_object(const nlohmann::json& obj, const Schema& s, const std::string& ptr, Ctx& ctx) {
  const nlohmann::json* saved = ctx.samplers;
  if (s.scopes_samplers) ctx.samplers = member(obj, "samplers");
  for (const Prop& p : s.props) {
    if (const nlohmann::json* v = member(obj, p.name))
      check_value(*v, p, child(ptr, p.name), ctx);
    else if (p.required)
      ctx.add(ptr.empty() ? "/" : ptr, "UNDEFINED_PROPERTY",
              "property '" + std::string(p.name) + "' is missing");
  }
  if (s.each != nullptr) {
    std::size_t members = 0;
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      if (it.key() == "extensions" || it.key() == "extras") continue;
      ++members;
      const std::string at = child(ptr, it.key());
      std::int64_t n = 0;
      if (s.each->kind == Kind::Index && !integer_of(it.value(), n))
        invalid_index(at, ctx);
      else
        check_value(it.value(), *s.each, at, ctx);
    }
    if (members < static_cast<std::size_t>(s.min_members))
      ctx.add(ptr, "EMPTY_ENTITY", "must not be empty");
  }
  if (const nlohmann::json* ext = member(obj, "extensions"))
    check_extensions(*ext, s.location, child(ptr, "extensions"), ctx);
  if (s.rule != nullptr) s.rule(obj, ptr, ctx);
  ctx.samplers = saved;
}

} // namespace irad::gltf::schema

namespace irad::gltf {

void check_schema(const nlohmann::json& root, std::vector<Issue>& issues) {
  schema::Ctx ctx{root, issues};
  if (!root.is_object()) return ctx.add("", "TYPE_MISMATCH", "the document is not a JSON object");
  schema::check_object(root, schema::kRoot, "", ctx);
}

} // namespace irad::gltf
