#include "core/gltf/validate/validate_semantics_read.h"

#include "core/gltf/read/accessors.h"
#include "core/gltf/read/json_read.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace irad::gltf::sem {

using nlohmann::json;

const json* member(const json& obj, std::string_view key) {
  if (!obj.is_object()) return nullptr;
  auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

const json* element(const json& obj, std::string_view key, std::int64_t i) {
  const json* a = member(obj, key);
  if (a == nullptr || !a->is_array() || i < 0 || static_cast<std::size_t>(i) >= a->size())
    return nullptr;
  return &(*a)[static_cast<std::size_t>(i)];
}

std::optional<std::int64_t> as_int(const json* v) {
  if (v == nullptr) return std::nullopt;
  if (v->is_number_integer()) {
    if (v->is_number_unsigned() &&
        v->get<std::uint64_t>() >
            static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
      return std::nullopt;
    return v->get<std::int64_t>();
  }
  if (v->is_number_float()) {
    const double d = v->get<double>();
    if (std::isfinite(d) && d == std::floor(d) && std::fabs(d) < 9.0e15)
      return static_cast<std::int64_t>(d);
  }
  return std::nullopt;
}

std::optional<std::int64_t> index(const json& obj, std::string_view key) {
  return as_int(member(obj, key));
}

std::optional<double> number(const json& obj, std::string_view key) {
  const json* v = member(obj, key);
  if (v == nullptr || !v->is_number()) return std::nullopt;
  return v->get<double>();
}

std::optional<std::string> string(const json& obj, std::string_view key) {
  const json* v = member(obj, key);
  if (v == nullptr || !v->is_string()) return std::nullopt;
  return v->get<std::string>();
}

bool boolean(const json& obj, std::string_view key) {
  const json* v = member(obj, key);
  return v != nullptr && v->is_boolean() && v->get<bool>();
}

std::size_t array_size(const json& obj, std::string_view key) {
  const json* v = member(obj, key);
  return v != nullptr && v->is_array() ? v->size() : 0;
}

std::optional<std::vector<double>> numbers(const json& obj, std::string_view key) {
  const json* v = member(obj, key);
  if (v == nullptr || !v->is_array()) return std::nullopt;
  std::vector<double> out;
  out.reserve(v->size());
  for (const json& e : *v) {
    if (!e.is_number()) return std::nullopt;
    out.push_back(e.get<double>());
  }
  return out;
}

bool has(const json& obj, std::string_view key) {
  return member(obj, key) != nullptr;
}

bool extension_used(const json& root, std::string_view name) {
  const json* used = member(root, "extensionsUsed");
  if (used == nullptr || !used->is_array()) return false;
  for (const json& e : *used)
    if (e.is_string() && e.get_ref<const std::string&>() == name) return true;
  return false;
}

std::string escape(std::string_view segment) {
  return pointer_escape(segment);
}

std::string at(const std::string& base, std::int64_t i) {
  return base + "/" + std::to_string(i);
}
std::string at(const std::string& base, std::string_view key) {
  return base + "/" + escape(key);
}

int component_size(std::int64_t component_type) {
  return component_type < 0 || component_type > 0xFFFF
             ? 0
             : int(gltf::component_size(int(component_type)));
}

int component_count(std::string_view type) {
  return int(gltf::component_count(std::string(type)));
}

const json& Context::list(std::string_view key) const {
  static const json empty = json::array(); // immutable
  const json* v = member(root, key);
  return v != nullptr && v->is_array() ? *v : empty;
}

const json* Context::object(std::string_view key, std::int64_t i) const {
  const json* v = element(root, key, i);
  return v != nullptr && v->is_object() ? v : nullptr;
}

namespace {

int matrix_rows(const AccessorView& a) {
  if (a.type == "MAT2") return 2;
  if (a.type == "MAT3") return 3;
  if (a.type == "MAT4") return 4;
  return 0;
}

// Bytes between two columns of a matrix element (columns start on 4-byte boundaries).
std::int64_t column_stride(const AccessorView& a) {
  const std::int64_t col = matrix_rows(a) * a.comp_size;
  return (col + 3) / 4 * 4;
}

// True when the bufferView's data is compressed by EXT_meshopt_compression or lies in a meshopt
// fallback buffer (whose bytes are not meaningful).
bool compressed_view(const Context& ctx, std::int64_t view) {
  const json* bv = ctx.object("bufferViews", view);
  if (bv == nullptr) return false;
  const json* ext = member(*bv, "extensions");
  if (ext != nullptr && has(*ext, "EXT_meshopt_compression")) return true;
  const auto buffer = index(*bv, "buffer");
  const json* b = buffer ? ctx.object("buffers", *buffer) : nullptr;
  const json* bext = b != nullptr ? member(*b, "extensions") : nullptr;
  return bext != nullptr && has(*bext, "EXT_meshopt_compression");
}

double read_component(const unsigned char* p, std::int64_t component_type) {
  switch (component_type) {
  case kByte:
    return static_cast<double>(static_cast<std::int8_t>(p[0]));
  case kUnsignedByte:
    return static_cast<double>(p[0]);
  case kShort: {
    std::int16_t v;
    std::memcpy(&v, p, 2);
    return v;
  }
  case kUnsignedShort: {
    std::uint16_t v;
    std::memcpy(&v, p, 2);
    return v;
  }
  case kUnsignedInt: {
    std::uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
  }
  default: {
    float v;
    std::memcpy(&v, p, 4);
    return static_cast<double>(v);
  }
  }
}

// The bytes [offset, offset + length) of bufferView `view`, or nullptr when they are not all
// there (view or buffer out of range, buffer absent or short).
const unsigned char* view_bytes(const Context& ctx, std::int64_t view, std::int64_t offset,
                                std::int64_t length) {
  const json* bv = ctx.object("bufferViews", view);
  if (bv == nullptr || offset < 0 || length < 0) return nullptr;
  const auto buffer = index(*bv, "buffer");
  const auto bv_length = index(*bv, "byteLength");
  const std::int64_t bv_offset = index(*bv, "byteOffset").value_or(0);
  if (!buffer || !bv_length || *buffer < 0 || !sane(bv_offset) || !sane(*bv_length) ||
      !sane(offset) || !sane(length) || static_cast<std::size_t>(*buffer) >= ctx.buffers.size())
    return nullptr;
  if (offset + length > *bv_length) return nullptr;
  const BufferBytes& b = ctx.buffers[static_cast<std::size_t>(*buffer)];
  if (!b.present || b.data == nullptr) return nullptr;
  if (static_cast<std::uint64_t>(bv_offset + offset + length) > b.size) return nullptr;
  return b.data + bv_offset + offset;
}

// The accessor's sparse substitutions, by element: entries in ascending element order, a later
// entry for the same element after an earlier one (it wins); elements outside [0, count) left
// out. nullopt when they cannot be read.
struct Substitutions {
  std::vector<std::pair<std::int64_t, std::size_t>> entries; // (element, k into values)
  std::vector<double> values;                                // components per entry
};
std::optional<Substitutions> read_sparse(const Context& ctx, const json& acc,
                                         const AccessorView& a) {
  const json* sparse = member(acc, "sparse");
  const auto count = sparse ? index(*sparse, "count") : std::nullopt;
  const json* indices = sparse ? member(*sparse, "indices") : nullptr;
  const json* vals = sparse ? member(*sparse, "values") : nullptr;
  if (!count || *count < 0 || *count > 0x1000000 || indices == nullptr || vals == nullptr)
    return std::nullopt;
  std::vector<double> idx;
  Substitutions out;
  const auto idx_type = index(*indices, "componentType").value_or(0);
  if (!read_packed(ctx, *indices, *count, idx_type, 1, idx)) return std::nullopt;
  if (!read_packed(ctx, *vals, *count, a.component_type, a.components, out.values))
    return std::nullopt;
  for (std::size_t k = 0; k < idx.size(); ++k)
    if (idx[k] >= 0 && idx[k] < static_cast<double>(a.count))
      out.entries.emplace_back(static_cast<std::int64_t>(idx[k]), k);
  std::stable_sort(out.entries.begin(), out.entries.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  return out;
}

// Elements per chunk of stream_accessor: at most 16 components each, 2 MiB of doubles.
constexpr std::int64_t kChunkElements = 1 << 14;

} // namespace

bool read_packed(const Context& ctx, const json& part, std::int64_t count,
                 std::int64_t component_type, int components, std::vector<double>& out) {
  const auto view = index(part, "bufferView");
  const int size = component_size(component_type);
  if (!view || size == 0 || compressed_view(ctx, *view)) return false;
  const std::int64_t offset = index(part, "byteOffset").value_or(0);
  if (!sane(count) || components <= 0 || components > 16) return false;
  const std::int64_t n = count * components;
  const unsigned char* p = view_bytes(ctx, *view, offset, n * size);
  if (p == nullptr) return false;
  out.resize(static_cast<std::size_t>(n));
  for (std::int64_t k = 0; k < n; ++k)
    out[static_cast<std::size_t>(k)] = read_component(p + k * size, component_type);
  return true;
}

std::optional<AccessorView> accessor_view(const Context& ctx, std::int64_t i) {
  const json* acc = ctx.object("accessors", i);
  if (acc == nullptr) return std::nullopt;
  AccessorView a;
  a.component_type = index(*acc, "componentType").value_or(0);
  a.type = string(*acc, "type").value_or("");
  a.components = component_count(a.type);
  a.comp_size = component_size(a.component_type);
  a.count = index(*acc, "count").value_or(-1);
  a.normalized = boolean(*acc, "normalized");
  a.buffer_view = index(*acc, "bufferView");
  a.byte_offset = index(*acc, "byteOffset").value_or(0);
  a.has_sparse = member(*acc, "sparse") != nullptr;
  a.valid = a.components > 0 && a.comp_size > 0 && sane(a.count) && sane(a.byte_offset);
  if (a.buffer_view) {
    if (const json* bv = ctx.object("bufferViews", *a.buffer_view))
      a.byte_stride = index(*bv, "byteStride");
    a.compressed = compressed_view(ctx, *a.buffer_view);
  }
  if (a.byte_stride && (*a.byte_stride <= 0 || *a.byte_stride > (std::int64_t{1} << 16)))
    a.valid = false; // the schema half reports it
  if (static_cast<std::size_t>(i) < ctx.draco_accessors.size() &&
      ctx.draco_accessors[static_cast<std::size_t>(i)] != 0)
    a.compressed = true;
  return a;
}

std::int64_t element_size(const AccessorView& a) {
  const int rows = matrix_rows(a);
  if (rows == 0) return std::int64_t{a.components} * a.comp_size;
  return rows * column_stride(a);
}

std::int64_t last_element_size(const AccessorView& a) {
  const int rows = matrix_rows(a);
  if (rows == 0) return element_size(a);
  return (rows - 1) * column_stride(a) + std::int64_t{rows} * a.comp_size;
}

bool stream_accessor(const Context& ctx, std::int64_t i, const AccessorSink& sink) {
  const auto a = accessor_view(ctx, i);
  if (!a || !a->valid || a->compressed) return false;
  // Without a bufferView the data is all zeros: the validator checks it only when sparse.
  if (!a->buffer_view && !a->has_sparse) return false;
  const unsigned char* p = nullptr;
  const std::int64_t stride = a->byte_stride.value_or(element_size(*a));
  if (a->buffer_view && a->count > 0) {
    // The bytes must all be there before any of them is decoded.
    const std::int64_t length = stride * (a->count - 1) + last_element_size(*a);
    p = view_bytes(ctx, *a->buffer_view, a->byte_offset, length);
    if (p == nullptr) return false;
  } else if (a->count > (std::int64_t{1} << 22)) {
    return false; // sparse over zeros: no bytes bound the count
  }
  std::optional<Substitutions> sparse;
  if (a->has_sparse && !(sparse = read_sparse(ctx, *ctx.object("accessors", i), *a))) return false;
  const auto n = static_cast<std::size_t>(a->components);
  const int rows = matrix_rows(*a);
  const std::int64_t col = rows == 0 ? 0 : column_stride(*a);
  std::vector<std::int64_t> offset(n); // of each component in an element
  for (std::size_t c = 0; c < n; ++c) {
    const auto ci = static_cast<std::int64_t>(c);
    offset[c] = rows == 0 ? ci * a->comp_size : (ci / rows) * col + (ci % rows) * a->comp_size;
  }
  std::vector<double> chunk;
  std::size_t next_sub = 0;
  for (std::int64_t first = 0; first < a->count; first += kChunkElements) {
    const std::int64_t last = std::min(a->count, first + kChunkElements);
    chunk.assign(static_cast<std::size_t>(last - first) * n, 0.0);
    if (p != nullptr)
      for (std::int64_t e = first; e < last; ++e)
        for (std::size_t c = 0; c < n; ++c)
          chunk[static_cast<std::size_t>(e - first) * n + c] =
              read_component(p + e * stride + offset[c], a->component_type);
    for (; sparse && next_sub < sparse->entries.size() && sparse->entries[next_sub].first < last;
         ++next_sub) {
      const auto [e, k] = sparse->entries[next_sub];
      for (std::size_t c = 0; c < n; ++c)
        chunk[static_cast<std::size_t>(e - first) * n + c] = sparse->values[k * n + c];
    }
    sink(chunk, first);
  }
  return true;
}

AccessorData read_accessor(const Context& ctx, std::int64_t i) {
  AccessorData out;
  out.ok = stream_accessor(ctx, i, [&out](std::span<const double> values, std::int64_t) {
    out.values.insert(out.values.end(), values.begin(), values.end());
  });
  if (!out.ok) out.values.clear();
  return out;
}

double normalize(double raw, std::int64_t component_type, bool normalized) {
  if (!normalized) return raw;
  switch (component_type) {
  case kByte:
    return std::max(raw / 127.0, -1.0);
  case kUnsignedByte:
    return raw / 255.0;
  case kShort:
    return std::max(raw / 32767.0, -1.0);
  case kUnsignedShort:
    return raw / 65535.0;
  default:
    return raw;
  }
}

} // namespace irad::gltf::sem
