#pragma once
// Internal to the semantic half of the validator (core/gltf/validate_semantics*.cpp): defensive
// readers of JSON values and of accessor data. Every function here accepts any JSON value (a
// wrong type reads as "absent") and never throws; the schema half reports the wrong types.
#include "core/gltf/validate/validate_parts.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace irad::gltf::sem {

// The member `key` of `obj` when obj is an object that has it, else nullptr.
const nlohmann::json* member(const nlohmann::json& obj, std::string_view key);
// Element i of the array `key` of `obj`, or nullptr.
const nlohmann::json* element(const nlohmann::json& obj, std::string_view key, std::int64_t i);
// The largest byte count, offset or element count the checks compute with: larger values (from
// fuzzed JSON) are treated as unreadable, so that sums and products cannot overflow.
inline constexpr std::int64_t kMaxSize = std::int64_t{1} << 40;
inline bool sane(std::int64_t v) {
  return v >= 0 && v <= kMaxSize;
}

// An integer value (a float with an integral value counts); nullopt otherwise.
std::optional<std::int64_t> as_int(const nlohmann::json* v);
std::optional<std::int64_t> index(const nlohmann::json& obj, std::string_view key);
std::optional<double> number(const nlohmann::json& obj, std::string_view key);
std::optional<std::string> string(const nlohmann::json& obj, std::string_view key);
bool boolean(const nlohmann::json& obj, std::string_view key); // false unless `true`
// The size of the array `key` (0 when absent or not an array).
std::size_t array_size(const nlohmann::json& obj, std::string_view key);
// The numbers of the array `key`; nullopt when it is not an array of numbers.
std::optional<std::vector<double>> numbers(const nlohmann::json& obj, std::string_view key);
bool has(const nlohmann::json& obj, std::string_view key);
// True when `name` is listed in root.extensionsUsed.
bool extension_used(const nlohmann::json& root, std::string_view name);

// JSON pointer segment escaping (~ → ~0, / → ~1).
std::string escape(std::string_view segment);
// "/" + a + "/" + std::to_string(i), e.g. at("/meshes", 2) == "/meshes/2".
std::string at(const std::string& base, std::int64_t i);
std::string at(const std::string& base, std::string_view key);

// glTF componentType codes.
enum : std::int64_t {
  kByte = 5120,
  kUnsignedByte = 5121,
  kShort = 5122,
  kUnsignedShort = 5123,
  kUnsignedInt = 5125,
  kFloat = 5126
};
int component_size(std::int64_t component_type); // 0 for an unknown type
int component_count(std::string_view type);      // 0 for an unknown type

// An accessor's layout, resolved as far as its JSON allows. `valid` when componentType, type and
// count are known; the data fields are set only when the bytes can be read.
struct AccessorView {
  bool valid = false; // also: count, byteOffset and byteStride (when set) are sane()
  std::int64_t component_type = 0;
  std::string type;
  int components = 0;     // 1..16
  int comp_size = 0;      // 1, 2 or 4
  std::int64_t count = 0; // >= 0
  bool normalized = false;
  std::optional<std::int64_t> buffer_view;
  std::int64_t byte_offset = 0;
  std::optional<std::int64_t> byte_stride; // the bufferView's byteStride
  bool has_sparse = false;
  bool compressed = false; // data lives in a compressed view (meshopt) or a Draco stream
};

struct Context;
// Reads accessor `i` (nullopt when out of range or not an object).
std::optional<AccessorView> accessor_view(const Context& ctx, std::int64_t i);
// Bytes of one element when packed (matrix columns padded to 4 bytes), and the bytes the last
// element needs (without the padding after the last column).
std::int64_t element_size(const AccessorView& a);
std::int64_t last_element_size(const AccessorView& a);

// The decoded components of an accessor: count * components values in element order (raw values
// for integer types, not normalised), with sparse substitution applied. Empty when the data
// cannot be read completely (missing buffer, out-of-range view, compressed, invalid layout) and
// when the accessor has neither bufferView nor sparse (its zeros are not checked).
struct AccessorData {
  bool ok = false;
  std::vector<double> values;
};
AccessorData read_accessor(const Context& ctx, std::int64_t i);
// The same values in element order, a chunk of whole elements at a time (at most 2 MiB of
// doubles): sink(values, first) gets elements [first, first + values.size() / components).
// Returns false, having called sink never, where read_accessor's data would be empty (whether
// the bytes and the sparse part are all there is known before the first chunk). The checks
// over mesh data use it: a mesh's accessors whole as doubles would be 8 bytes per component.
using AccessorSink = std::function<void(std::span<const double> values, std::int64_t first)>;
bool stream_accessor(const Context& ctx, std::int64_t i, const AccessorSink& sink);

// Reads `count` tightly packed elements of `components` values from the bufferView and
// byteOffset named in `part` (a sparse accessor's indices or values); false when not all there.
bool read_packed(const Context& ctx, const nlohmann::json& part, std::int64_t count,
                 std::int64_t component_type, int components, std::vector<double>& out);

// The value of a normalised (or float) component as a float in [-1, 1] / [0, 1].
double normalize(double raw, std::int64_t component_type, bool normalized);

// Shared state of one check_semantics run: the inputs and the issue list.
struct Context {
  const nlohmann::json& root;
  const std::vector<BufferBytes>& buffers;
  std::vector<Issue>& issues;
  // Per accessor: 1 when a Draco-compressed primitive uses it (its data is not in its view).
  std::vector<char> draco_accessors;
  // extensions: Issue::extensions.
  void add(std::string pointer, std::string code, std::string message,
           std::vector<std::string> extensions = {}) const {
    issues.push_back(
        {std::move(pointer), std::move(code), std::move(message), std::move(extensions)});
  }
  // root[key] as an array (an empty array when absent or of another type).
  const nlohmann::json& list(std::string_view key) const;
  // root[key][i] when it is an object, else nullptr.
  const nlohmann::json* object(std::string_view key, std::int64_t i) const;
};

// The parts of check_semantics, each in its own file.
void check_buffers(const Context& ctx);    // validate_semantics_buffers.cpp
void check_accessors(const Context& ctx);  // validate_accessors.cpp
void check_meshes(const Context& ctx);     // validate_meshes.cpp
void check_mesh_data(const Context& ctx);  // validate_mesh_data.cpp
void check_nodes(const Context& ctx);      // validate_nodes.cpp
void check_skins(const Context& ctx);      // validate_nodes.cpp
void check_animations(const Context& ctx); // validate_animations.cpp
void check_images(const Context& ctx);     // validate_semantics_buffers.cpp

} // namespace irad::gltf::sem
