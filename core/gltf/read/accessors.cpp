#include "core/gltf/read/accessors.h"

#include "core/gltf/decode/codecs.h"
#include "core/util/freed_memory.h"
#include "core/util/parallel_rows.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fmt/format.h>

namespace irad::gltf {

namespace {

// The largest accessor we materialise without backing data (no bufferView), in bytes.
constexpr std::size_t kMaxSyntheticBytes = std::size_t(1) << 30;

// True when offset + stride (count - 1) + size <= length, computed without overflow (count >= 1).
bool fits(std::size_t offset, std::size_t stride, std::size_t count, std::size_t size,
          std::size_t length) {
  if (size > length || offset > length - size) return false;
  const std::size_t room = length - size - offset;
  return count <= 1 || (stride > 0 && count - 1 <= room / stride);
}

// EXT_meshopt_compression of bufferViews[v]: its bytes decoded into ctx.decoded_views.
const std::vector<unsigned char>& meshopt_view(const Context& ctx, std::size_t v, const json& ext,
                                               const std::string& name) {
  if (const auto found = ctx.decoded_views.find(v); found != ctx.decoded_views.end())
    return found->second;
  const std::string where = name + ".extensions.EXT_meshopt_compression";
  const std::size_t b =
      checked_index(ctx, static_cast<long long>(index_member(ext, "buffer").value_or(~0ull >> 1)),
                    ctx.buffers.size(), where, "buffer");
  ctx.use("buffers", b);
  const BufferData& buffer = ctx.buffers[b];
  if (!buffer.present) ctx.fail(element("buffers", b), "has no data");
  const std::uint64_t offset = index_member(ext, "byteOffset").value_or(0);
  const std::uint64_t length = index_member(ext, "byteLength").value_or(0);
  const std::uint64_t stride = index_member(ext, "byteStride").value_or(0);
  const std::uint64_t count = index_member(ext, "count").value_or(0);
  if (length > buffer.bytes().size() || offset > buffer.bytes().size() - length)
    ctx.fail(where, "byteOffset + byteLength exceed the buffer");
  if (stride == 0 || count == 0 || count > 3 * ctx.limits.max_triangles * 4 || stride > 256)
    ctx.fail(where, "count and byteStride must be positive (byteStride at most 256)");
  try {
    auto decoded = decode_meshopt(buffer.bytes().data() + offset, length, count, stride,
                                  string_member(ext, "mode"), string_member(ext, "filter", "NONE"));
    return ctx.decoded_views[v] = std::move(decoded);
  } catch (const CodecError& e) {
    ctx.fail(where, e.what());
  }
}

// A view into a placeholder buffer: zeros, with a warning.
ViewBytes placeholder_view(const Context& ctx, std::size_t v, std::size_t b, std::uint64_t offset,
                           std::uint64_t length, std::size_t stride) {
  const BufferData& buffer = ctx.buffers[b];
  if (length > buffer.byte_length || offset > buffer.byte_length - length)
    ctx.fail(element("bufferViews", v), "exceeds its buffer's byteLength");
  if (length > (std::uint64_t(1) << 30)) ctx.fail(element("bufferViews", v), "too large");
  ctx.warn(element("buffers", b) + ": no uri and no data; its bytes are read as zeros");
  auto& zeros = ctx.decoded_views[v];
  zeros.assign(std::size_t(length), 0);
  return {zeros.data(), zeros.size(), stride};
}

} // namespace

ViewBytes view_bytes(const Context& ctx, std::uint64_t view, const std::string& where) {
  const std::size_t v = checked_index(ctx, view > 0x7fffffffull ? -1 : static_cast<long long>(view),
                                      ctx.count("bufferViews"), where, "bufferView");
  const json& bv = ctx.array("bufferViews")[v];
  // The buffer first: a problem there explains the view's.
  if (const auto b = index_member(bv, "buffer"); b && *b < ctx.buffers.size())
    ctx.use("buffers", std::size_t(*b));
  ctx.use("bufferViews", v);
  const std::string name = element("bufferViews", v);
  const std::size_t stride = index_member(bv, "byteStride").value_or(0);
  if (const json* ext = extension(bv, "EXT_meshopt_compression")) {
    const std::vector<unsigned char>& bytes = meshopt_view(ctx, v, *ext, name);
    return {bytes.data(), bytes.size(), stride};
  }
  const std::size_t b =
      checked_index(ctx, static_cast<long long>(index_member(bv, "buffer").value_or(~0ull >> 1)),
                    ctx.buffers.size(), name, "buffer");
  ctx.use("buffers", b);
  const BufferData& buffer = ctx.buffers[b];
  const std::uint64_t offset = index_member(bv, "byteOffset").value_or(0);
  const std::uint64_t length = index_member(bv, "byteLength").value_or(0);
  if (buffer.placeholder) return placeholder_view(ctx, v, b, offset, length, stride);
  if (!buffer.present) ctx.fail(element("buffers", b), "has no data");
  const std::size_t size = buffer.bytes().size();
  if (length > size || offset > size - length) {
    ctx.fail(name, fmt::format("byteOffset {} + byteLength {} exceeds the buffer's {} bytes",
                               offset, length, size));
  }
  return {buffer.bytes().data() + offset, std::size_t(length), stride};
}

namespace {

// The elements of one accessor: element i starts at at(i).
struct Elements {
  const unsigned char* base = nullptr;
  std::size_t stride = 0;
  std::size_t size = 0; // bytes of one element (with matrix column padding)
  std::size_t count = 0;
  std::vector<unsigned char> dense; // owns the bytes of sparse or zero-filled accessors
  const unsigned char* at(std::size_t i) const {
    return (dense.empty() ? base : dense.data()) + i * stride;
  }
};

// The layout of an accessor: component type, number and the element size. Matrices of 1- and
// 2-byte components pad each column to 4 bytes (glTF 3.6.2.4).
struct Layout {
  int component_type = 0;
  std::size_t csize = 0;
  std::size_t components = 0;
  std::size_t rows = 0; // of a matrix column; = components otherwise
  std::size_t column_stride = 0;
  std::size_t size = 0;
  bool normalized = false;
  std::string type;
  std::size_t offset_of(std::size_t k) const { return k / rows * column_stride + k % rows * csize; }
};

Layout layout_of(const Context& ctx, const json& a, const std::string& name) {
  Layout l;
  l.component_type = int(number_member(a, "componentType", 0));
  l.type = string_member(a, "type");
  l.csize = component_size(l.component_type);
  l.components = component_count(l.type);
  if (l.csize == 0 || l.components == 0) ctx.fail(name, "unsupported componentType or type");
  l.rows = l.type == "MAT2" ? 2 : l.type == "MAT3" ? 3 : l.type == "MAT4" ? 4 : l.components;
  l.column_stride = (l.rows * l.csize + 3) / 4 * 4;
  if (l.rows == l.components) l.column_stride = l.rows * l.csize;
  l.size = l.column_stride * (l.components / l.rows);
  l.normalized = bool_member(a, "normalized", false);
  return l;
}

void attach_view(const Context& ctx, const json& a, std::uint64_t view, const std::string& name,
                 Elements& e) {
  const ViewBytes v = view_bytes(ctx, view, name);
  e.stride = v.stride != 0 ? v.stride : e.size;
  if (e.stride < e.size) {
    ctx.fail(name,
             fmt::format("byteStride {} is smaller than the element size {}", e.stride, e.size));
  }
  const std::uint64_t offset = index_member(a, "byteOffset").value_or(0);
  if (offset > v.length || !fits(std::size_t(offset), e.stride, e.count, e.size, v.length)) {
    ctx.fail(name, fmt::format("byteOffset {} + stride {} * (count {} - 1) + element size {} "
                               "exceeds the byteLength {} of bufferViews[{}]",
                               offset, e.stride, e.count, e.size, v.length, view));
  }
  e.base = v.data + offset;
}

// Copies the elements into e.dense (tightly packed), zero-filled without a bufferView.
void densify(const Context& ctx, const std::string& name, Elements& e) {
  if (e.count > kMaxSyntheticBytes / e.size) ctx.fail(name, "accessor too large");
  std::vector<unsigned char> dense(e.count * e.size, 0);
  if (e.base != nullptr) {
    for (std::size_t i = 0; i < e.count; ++i) std::memcpy(&dense[i * e.size], e.at(i), e.size);
  }
  e.dense = std::move(dense);
  e.stride = e.size;
}

std::uint32_t read_uint(const unsigned char* p, int component_type) {
  if (component_type == kUnsignedByte) return *p;
  if (component_type == kUnsignedShort) {
    std::uint16_t v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  std::uint32_t v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Overwrites the elements listed by accessor.sparse (glTF sparse storage) in e.dense.
void apply_sparse(const Context& ctx, const json& s, const std::string& name, Elements& e) {
  const std::uint64_t n = index_member(s, "count").value_or(0);
  if (n < 1 || n > e.count)
    ctx.fail(name, fmt::format("sparse.count {} must lie in [1, count]", n));
  const json* indices = member(s, "indices");
  const json* values = member(s, "values");
  if (!indices || !values) ctx.fail(name, "sparse needs indices and values");
  const int itype = int(number_member(*indices, "componentType", 0));
  if (itype != kUnsignedByte && itype != kUnsignedShort && itype != kUnsignedInt)
    ctx.fail(name, "sparse.indices.componentType must be an unsigned integer type");
  const std::size_t isize = component_size(itype);
  const ViewBytes iv = view_bytes(ctx, index_member(*indices, "bufferView").value_or(~0ull),
                                  name + ".sparse.indices");
  const ViewBytes vv =
      view_bytes(ctx, index_member(*values, "bufferView").value_or(~0ull), name + ".sparse.values");
  const std::uint64_t ioff = index_member(*indices, "byteOffset").value_or(0);
  const std::uint64_t voff = index_member(*values, "byteOffset").value_or(0);
  if (ioff > iv.length || !fits(std::size_t(ioff), isize, n, isize, iv.length))
    ctx.fail(name, "sparse.indices exceed their bufferView");
  if (voff > vv.length || !fits(std::size_t(voff), e.size, n, e.size, vv.length))
    ctx.fail(name, "sparse.values exceed their bufferView");
  const unsigned char* ip = iv.data + ioff;
  const unsigned char* vp = vv.data + voff;
  for (std::size_t j = 0; j < n; ++j) {
    const std::uint32_t target = read_uint(ip + j * isize, itype);
    if (target >= e.count) {
      ctx.fail(name, fmt::format("sparse index {} out of range (count {})", target, e.count));
    }
    if (j > 0 && target <= read_uint(ip + (j - 1) * isize, itype)) {
      ctx.fail(name, fmt::format("sparse indices must increase strictly (at {})", target));
    }
    std::memcpy(&e.dense[target * e.size], vp + j * e.size, e.size);
  }
}

// The accessor's JSON after use() and a range check.
const json& accessor_json(const Context& ctx, std::uint64_t index, const std::string& use) {
  return ctx.at("accessors", index, use, "accessor");
}

// Checked elements of accessor `index` with layout `l`.
Elements elements(const Context& ctx, std::uint64_t index, const Layout& l) {
  const json& a = ctx.array("accessors")[std::size_t(index)];
  const std::string name = element("accessors", std::size_t(index));
  Elements e;
  e.size = l.size;
  const std::uint64_t count = index_member(a, "count").value_or(0);
  if (count < 1) ctx.fail(name, "count must be >= 1");
  if (count > 3 * ctx.limits.max_triangles) {
    ctx.fail(name, fmt::format("count {} is over the limit of 3 x {} elements (--max-triangles)",
                               count, ctx.limits.max_triangles));
  }
  e.count = std::size_t(count);
  if (const auto d = ctx.decoded_accessors.find(std::size_t(index));
      d != ctx.decoded_accessors.end()) {
    if (d->second.size() != e.count * e.size) ctx.fail(name, "decoded data of the wrong size");
    e.base = d->second.data();
    e.stride = e.size;
    return e;
  }
  const std::optional<std::uint64_t> view = index_member(a, "bufferView");
  const json* sparse = member(a, "sparse");
  if (view) attach_view(ctx, a, *view, name, e);
  if (!view || sparse) densify(ctx, name, e);
  if (sparse) apply_sparse(ctx, *sparse, name, e);
  return e;
}

float read_component(const unsigned char* p, int type, bool normalized) {
  switch (type) {
  case kFloat: {
    float v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  case kByte: {
    const float v = float(static_cast<std::int8_t>(*p));
    return normalized ? std::max(v / 127.0f, -1.0f) : v;
  }
  case kShort: {
    std::int16_t s;
    std::memcpy(&s, p, sizeof s);
    return normalized ? std::max(float(s) / 32767.0f, -1.0f) : float(s);
  }
  case kUnsignedByte:
    return normalized ? float(*p) / 255.0f : float(*p);
  case kUnsignedShort: {
    std::uint16_t u;
    std::memcpy(&u, p, sizeof u);
    return normalized ? float(u) / 65535.0f : float(u);
  }
  default: {
    std::uint32_t u;
    std::memcpy(&u, p, sizeof u);
    return normalized ? float(double(u) / 4294967295.0) : float(u);
  }
  }
}

bool listed(const std::string& s, std::initializer_list<const char*> list) {
  return std::any_of(list.begin(), list.end(), [&](const char* x) { return s == x; });
}

std::string expected_text(std::initializer_list<const char*> types,
                          std::initializer_list<int> component_types, bool normalized_only) {
  std::string t;
  for (const char* x : types) {
    if (!t.empty()) t += '/';
    t += x;
  }
  std::string c;
  for (int x : component_types) {
    if (!c.empty()) c += '/';
    c += std::to_string(x);
  }
  return t + " of componentType " + c + (normalized_only ? " (integers normalized)" : "");
}

} // namespace

std::size_t component_size(int component_type) {
  switch (component_type) {
  case kByte:
  case kUnsignedByte:
    return 1;
  case kShort:
  case kUnsignedShort:
    return 2;
  case kUnsignedInt:
  case kFloat:
    return 4;
  default:
    return 0;
  }
}

std::size_t component_count(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  if (type == "MAT4") return 16;
  return 0;
}

std::size_t accessor_count(const Context& ctx, std::uint64_t accessor, const std::string& use) {
  return std::size_t(index_member(accessor_json(ctx, accessor, use), "count").value_or(0));
}

namespace {

// The accessor's elements checked against the use's types (as read_values), decoded into
// `out` as floats, `components` per element; out is sized here. T: float or a glm vector of
// `components` floats.
template <class T>
void decode_floats(const Context& ctx, std::uint64_t accessor, const std::string& use,
                   std::initializer_list<const char*> types,
                   std::initializer_list<int> component_types, bool normalized_only,
                   std::vector<T>& out, std::size_t* components = nullptr) {
  const json& a = accessor_json(ctx, accessor, use);
  const std::string name = element("accessors", std::size_t(accessor));
  const Layout l = layout_of(ctx, a, name);
  const bool type_ok = listed(l.type, types);
  const bool component_ok = std::find(component_types.begin(), component_types.end(),
                                      l.component_type) != component_types.end();
  const bool norm_ok = !normalized_only || l.component_type == kFloat || l.normalized;
  if (!type_ok || !component_ok || !norm_ok) {
    ctx.fail(name, "used as " + use + ", must be " +
                       expected_text(types, component_types, normalized_only));
  }
  const Elements e = elements(ctx, accessor, l);
  const std::size_t floats_per_t = sizeof(T) / sizeof(float);
  if (components) *components = l.components;
  resize_huge(out, e.count * l.components / floats_per_t);
  auto* dst = reinterpret_cast<float*>(out.data());
  parallel_chunks(e.count, [&](std::size_t first, std::size_t end) {
    for (std::size_t i = first; i < end; ++i) {
      const unsigned char* p = e.at(i);
      for (std::size_t k = 0; k < l.components; ++k)
        dst[i * l.components + k] =
            read_component(p + l.offset_of(k), l.component_type, l.normalized);
    }
  });
}

} // namespace

Values read_values(const Context& ctx, std::uint64_t accessor, const std::string& use,
                   std::initializer_list<const char*> types,
                   std::initializer_list<int> component_types, bool normalized_only) {
  Values out;
  decode_floats(ctx, accessor, use, types, component_types, normalized_only, out.data,
                &out.components);
  return out;
}

std::vector<glm::vec3> read_vec3(const Context& ctx, std::uint64_t accessor,
                                 const std::string& use) {
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  std::vector<glm::vec3> out; // straight into vec3s: the type check admits VEC3 only
  decode_floats(ctx, accessor, use, {"VEC3"},
                {kByte, kUnsignedByte, kShort, kUnsignedShort, kFloat}, false, out);
  return out;
}

std::vector<glm::vec2> read_texcoords(const Context& ctx, std::uint64_t accessor,
                                      const std::string& use) {
  static_assert(sizeof(glm::vec2) == 2 * sizeof(float));
  std::vector<glm::vec2> out;
  decode_floats(ctx, accessor, use, {"VEC2"},
                {kByte, kUnsignedByte, kShort, kUnsignedShort, kFloat}, false, out);
  return out;
}

std::vector<glm::vec4> read_colors(const Context& ctx, std::uint64_t accessor,
                                   const std::string& use) {
  const Values v = read_values(ctx, accessor, use, {"VEC3", "VEC4"},
                               {kUnsignedByte, kUnsignedShort, kFloat}, true);
  std::vector<glm::vec4> out(v.count(), glm::vec4(1.0f));
  for (std::size_t i = 0; i < out.size(); ++i)
    for (std::size_t k = 0; k < v.components; ++k) {
      const float c = v.data[i * v.components + k];
      out[i][int(k)] = std::isfinite(c) ? std::clamp(c, 0.0f, 1.0f) : 0.0f;
    }
  return out;
}

std::vector<glm::vec4> read_animation_values(const Context& ctx, std::uint64_t accessor,
                                             const std::string& use, const char* type) {
  const bool scalar = std::string(type) == "SCALAR";
  const Values v = scalar
                       ? read_values(ctx, accessor, use, {"SCALAR"}, {kFloat})
                       : read_values(ctx, accessor, use, {type},
                                     {kByte, kUnsignedByte, kShort, kUnsignedShort, kFloat}, true);
  std::vector<glm::vec4> out(v.count(), glm::vec4(0.0f));
  for (std::size_t i = 0; i < out.size(); ++i)
    for (std::size_t k = 0; k < v.components; ++k) {
      const float x = v.data[i * v.components + k];
      if (!std::isfinite(x))
        ctx.fail(element("accessors", std::size_t(accessor)), "non-finite value");
      out[i][int(k)] = x;
    }
  return out;
}

namespace {

// The index accessor's elements, after checking that it is a SCALAR of unsigned bytes, shorts or
// ints; `component_type` receives which.
Elements index_elements(const Context& ctx, std::uint64_t accessor, const std::string& use,
                        int& component_type) {
  const json& a = accessor_json(ctx, accessor, use);
  const std::string name = element("accessors", std::size_t(accessor));
  const Layout l = layout_of(ctx, a, name);
  if (l.type != "SCALAR" ||
      (l.component_type != kUnsignedByte && l.component_type != kUnsignedShort &&
       l.component_type != kUnsignedInt)) {
    ctx.fail(name, "used as " + use +
                       ", must be a SCALAR accessor of unsigned bytes, shorts or "
                       "ints");
  }
  component_type = l.component_type;
  return elements(ctx, accessor, l);
}

// The first `count` index values of `e` into `out`, on all cores.
void copy_indices(const Elements& e, int component_type, std::size_t count, std::uint32_t* out) {
  parallel_chunks(count, [&](std::size_t first, std::size_t end) {
    for (std::size_t i = first; i < end; ++i) out[i] = read_uint(e.at(i), component_type);
  });
}

} // namespace

std::vector<std::uint32_t> read_indices(const Context& ctx, std::uint64_t accessor,
                                        const std::string& use) {
  int type = 0;
  const Elements e = index_elements(ctx, accessor, use, type);
  std::vector<std::uint32_t> out;
  resize_huge(out, e.count);
  copy_indices(e, type, e.count, out.data());
  return out;
}

std::vector<glm::uvec3> read_index_triples(const Context& ctx, std::uint64_t accessor,
                                           const std::string& use) {
  static_assert(sizeof(glm::uvec3) == 3 * sizeof(std::uint32_t));
  int type = 0;
  const Elements e = index_elements(ctx, accessor, use, type);
  std::vector<glm::uvec3> out;
  resize_huge(out, e.count / 3);
  copy_indices(e, type, 3 * out.size(), reinterpret_cast<std::uint32_t*>(out.data()));
  return out;
}

} // namespace irad::gltf
