#include "core/gltf/accessors.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace irad::gltf {

namespace {

constexpr int kUnsignedByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kUnsignedShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kUnsignedInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
// The largest accessor we materialise without backing data (no bufferView), in bytes.
constexpr std::size_t kMaxSyntheticBytes = std::size_t(1) << 30;

// Size in bytes of a glTF component type; 0 for types glTF 2.0 does not define.
std::size_t component_size(int component_type) {
  switch (component_type) {
  case TINYGLTF_COMPONENT_TYPE_BYTE:
  case kUnsignedByte:
    return 1;
  case TINYGLTF_COMPONENT_TYPE_SHORT:
  case kUnsignedShort:
    return 2;
  case kUnsignedInt:
  case kFloat:
    return 4;
  default:
    return 0;
  }
}

// Number of components of a glTF accessor type (SCALAR 1 ... MAT4 16); 0 if unknown.
std::size_t component_count(int type) {
  const int n = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(type));
  return n > 0 ? std::size_t(n) : 0;
}

// True when offset + stride (count - 1) + size <= length, computed without overflow (count >= 1).
bool fits(std::size_t offset, std::size_t stride, std::size_t count, std::size_t size,
          std::size_t length) {
  if (size > length || offset > length - size) return false;
  const std::size_t room = length - size - offset;
  return count <= 1 || (stride > 0 && count - 1 <= room / stride);
}

// The bytes of a bufferView after checking its buffer index and its range within buffer.data.
struct ViewBytes {
  const unsigned char* data;
  std::size_t length;
  std::size_t stride; // 0: tightly packed
};

ViewBytes view_bytes(const Context& ctx, int view, const std::string& where) {
  const auto& views = ctx.model.bufferViews;
  const std::size_t v = checked_index(ctx, view, views.size(), where, "bufferView");
  const tinygltf::BufferView& bv = views[v];
  const std::string name = element("bufferViews", v);
  const auto& buffer =
      ctx.model.buffers[checked_index(ctx, bv.buffer, ctx.model.buffers.size(), name, "buffer")];
  const std::size_t size = buffer.data.size();
  if (bv.byteLength > size || bv.byteOffset > size - bv.byteLength) {
    ctx.fail(name, "byteOffset " + std::to_string(bv.byteOffset) + " + byteLength " +
                       std::to_string(bv.byteLength) + " exceeds the buffer's " +
                       std::to_string(size) + " bytes");
  }
  return {buffer.data.data() + bv.byteOffset, bv.byteLength, bv.byteStride};
}

// The elements of one accessor: element i starts at at(i) and has `size` bytes.
struct Elements {
  const unsigned char* base = nullptr;
  std::size_t stride = 0;
  std::size_t size = 0;
  std::size_t count = 0;
  std::vector<unsigned char> dense; // owns the bytes of sparse or zero-filled accessors
  const unsigned char* at(std::size_t i) const {
    return (dense.empty() ? base : dense.data()) + i * stride;
  }
};

// Dense backing of an accessor with a bufferView: checks stride and range.
void attach_view(const Context& ctx, const tinygltf::Accessor& a, const std::string& name,
                 Elements& e) {
  const ViewBytes v = view_bytes(ctx, a.bufferView, name);
  e.stride = v.stride != 0 ? v.stride : e.size;
  if (e.stride < e.size) {
    ctx.fail(name, "byteStride " + std::to_string(e.stride) + " is smaller than the element size " +
                       std::to_string(e.size));
  }
  if (!fits(a.byteOffset, e.stride, e.count, e.size, v.length)) {
    ctx.fail(name, "byteOffset " + std::to_string(a.byteOffset) + " + stride " +
                       std::to_string(e.stride) + " * (count " + std::to_string(e.count) +
                       " - 1) + element size " + std::to_string(e.size) +
                       " exceeds the byteLength " + std::to_string(v.length) + " of bufferViews[" +
                       std::to_string(a.bufferView) + "]");
  }
  e.base = v.data + a.byteOffset;
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

std::uint32_t read_index(const unsigned char* p, int component_type) {
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
void apply_sparse(const Context& ctx, const tinygltf::Accessor& a, const std::string& name,
                  Elements& e) {
  const auto& s = a.sparse;
  if (s.count < 1 || std::size_t(s.count) > e.count) {
    ctx.fail(name, "sparse.count " + std::to_string(s.count) + " must lie in [1, count]");
  }
  const std::size_t n = std::size_t(s.count);
  const std::size_t isize = component_size(s.indices.componentType);
  if (isize == 0 || s.indices.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
      s.indices.componentType == TINYGLTF_COMPONENT_TYPE_SHORT) {
    ctx.fail(name, "sparse.indices.componentType must be an unsigned integer type");
  }
  const ViewBytes iv = view_bytes(ctx, s.indices.bufferView, name + ".sparse.indices");
  const ViewBytes vv = view_bytes(ctx, s.values.bufferView, name + ".sparse.values");
  if (s.indices.byteOffset < 0 ||
      !fits(std::size_t(s.indices.byteOffset), isize, n, isize, iv.length)) {
    ctx.fail(name, "sparse.indices exceed their bufferView");
  }
  if (s.values.byteOffset < 0 ||
      !fits(std::size_t(s.values.byteOffset), e.size, n, e.size, vv.length)) {
    ctx.fail(name, "sparse.values exceed their bufferView");
  }
  const unsigned char* indices = iv.data + s.indices.byteOffset;
  const unsigned char* values = vv.data + s.values.byteOffset;
  for (std::size_t j = 0; j < n; ++j) {
    const std::uint32_t target = read_index(indices + j * isize, s.indices.componentType);
    if (target >= e.count) {
      ctx.fail(name, "sparse index " + std::to_string(target) + " out of range (count " +
                         std::to_string(e.count) + ")");
    }
    if (j > 0 && target <= read_index(indices + (j - 1) * isize, s.indices.componentType)) {
      ctx.fail(name, "sparse indices must increase strictly (overlapping substitutions at " +
                         std::to_string(target) + ")");
    }
    std::memcpy(&e.dense[target * e.size], values + j * e.size, e.size);
  }
}

// Validated elements of accessor `index`; `use` names the referring element for messages.
Elements elements(const Context& ctx, int index, const std::string& use) {
  const std::size_t i = checked_index(ctx, index, ctx.model.accessors.size(), use, "accessor");
  const tinygltf::Accessor& a = ctx.model.accessors[i];
  const std::string name = element("accessors", i);
  Elements e;
  e.size = component_size(a.componentType) * component_count(a.type);
  if (e.size == 0) ctx.fail(name, "unsupported componentType or type");
  if (a.count < 1) ctx.fail(name, "count must be >= 1");
  if (a.count > 3 * ctx.limits.max_triangles) {
    ctx.fail(name, "count " + std::to_string(a.count) + " is over the limit of 3 x " +
                       std::to_string(ctx.limits.max_triangles) + " elements (--max-triangles)");
  }
  e.count = a.count;
  if (a.bufferView >= 0) attach_view(ctx, a, name, e);
  if (a.bufferView < 0 || a.sparse.isSparse) densify(ctx, name, e);
  if (a.sparse.isSparse) apply_sparse(ctx, a, name, e);
  return e;
}

// Fails unless accessor `index` exists and has the given type and one of the allowed component
// types (checked before its data: the type decides the element size).
void require_layout(const Context& ctx, int index, const std::string& use, int type,
                    std::initializer_list<int> component_types, const std::string& expected) {
  checked_index(ctx, index, ctx.model.accessors.size(), use, "accessor");
  const tinygltf::Accessor& a = ctx.model.accessors[std::size_t(index)];
  bool ok = a.type == type;
  bool component_ok = false;
  for (int c : component_types) component_ok = component_ok || a.componentType == c;
  if (!ok || !component_ok) {
    ctx.fail(element("accessors", std::size_t(index)), "used as " + use + ", must be " + expected);
  }
}

float read_float(const unsigned char* p) {
  float v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Normalized unsigned integer component to [0, 1] (glTF: c / (2^bits - 1)).
float read_unorm(const unsigned char* p, int component_type) {
  if (component_type == kUnsignedByte) return float(*p) / 255.0f;
  std::uint16_t v;
  std::memcpy(&v, p, sizeof v);
  return float(v) / 65535.0f;
}

// Normalized component (any glTF integer type, signed: max(c / (2^(bits-1) - 1), -1)) or float.
float read_normalized(const unsigned char* p, int component_type) {
  switch (component_type) {
  case kFloat:
    return read_float(p);
  case TINYGLTF_COMPONENT_TYPE_BYTE:
    return std::max(float(static_cast<std::int8_t>(*p)) / 127.0f, -1.0f);
  case TINYGLTF_COMPONENT_TYPE_SHORT: {
    std::int16_t v;
    std::memcpy(&v, p, sizeof v);
    return std::max(float(v) / 32767.0f, -1.0f);
  }
  default:
    return read_unorm(p, component_type);
  }
}

} // namespace

std::vector<glm::vec3> read_vec3(const Context& ctx, int accessor, const std::string& use) {
  require_layout(ctx, accessor, use, TINYGLTF_TYPE_VEC3, {kFloat}, "a float VEC3 accessor");
  const Elements e = elements(ctx, accessor, use);
  std::vector<glm::vec3> out(e.count);
  for (std::size_t i = 0; i < e.count; ++i) {
    const unsigned char* p = e.at(i);
    out[i] = {read_float(p), read_float(p + 4), read_float(p + 8)};
  }
  return out;
}

std::vector<glm::vec2> read_texcoords(const Context& ctx, int accessor, const std::string& use) {
  const std::string expected = "a VEC2 accessor of floats or normalized unsigned bytes/shorts";
  require_layout(ctx, accessor, use, TINYGLTF_TYPE_VEC2, {kFloat, kUnsignedByte, kUnsignedShort},
                 expected);
  const tinygltf::Accessor& a = ctx.model.accessors[std::size_t(accessor)];
  if (a.componentType != kFloat && !a.normalized) {
    ctx.fail(element("accessors", std::size_t(accessor)),
             "used as " + use + ", must be " + expected);
  }
  const Elements e = elements(ctx, accessor, use);
  const std::size_t c = component_size(a.componentType);
  std::vector<glm::vec2> out(e.count);
  for (std::size_t i = 0; i < e.count; ++i) {
    const unsigned char* p = e.at(i);
    out[i] = a.componentType == kFloat
                 ? glm::vec2(read_float(p), read_float(p + 4))
                 : glm::vec2(read_unorm(p, a.componentType), read_unorm(p + c, a.componentType));
  }
  return out;
}

std::vector<glm::vec4> read_animation_values(const Context& ctx, int accessor,
                                             const std::string& use, int type) {
  const bool vec4 = type == TINYGLTF_TYPE_VEC4;
  const std::string expected = type == TINYGLTF_TYPE_SCALAR ? "a float SCALAR accessor"
                               : vec4 ? "a VEC4 accessor of floats or normalized integers"
                                      : "a float VEC3 accessor";
  require_layout(ctx, accessor, use, type,
                 vec4 ? std::initializer_list<int>{kFloat, TINYGLTF_COMPONENT_TYPE_BYTE,
                                                   kUnsignedByte, TINYGLTF_COMPONENT_TYPE_SHORT,
                                                   kUnsignedShort}
                      : std::initializer_list<int>{kFloat},
                 expected);
  const tinygltf::Accessor& a = ctx.model.accessors[std::size_t(accessor)];
  if (a.componentType != kFloat && !a.normalized) {
    ctx.fail(element("accessors", std::size_t(accessor)),
             "used as " + use + ", must be " + expected);
  }
  const Elements e = elements(ctx, accessor, use);
  const std::size_t c = component_size(a.componentType);
  const std::size_t n = component_count(type);
  std::vector<glm::vec4> out(e.count, glm::vec4(0.0f));
  for (std::size_t i = 0; i < e.count; ++i) {
    const unsigned char* p = e.at(i);
    for (std::size_t k = 0; k < n; ++k) {
      const float v = read_normalized(p + k * c, a.componentType);
      if (!std::isfinite(v))
        ctx.fail(element("accessors", std::size_t(accessor)), "non-finite value");
      out[i][int(k)] = v;
    }
  }
  return out;
}

std::vector<std::uint32_t> read_indices(const Context& ctx, int accessor, const std::string& use) {
  require_layout(ctx, accessor, use, TINYGLTF_TYPE_SCALAR,
                 {kUnsignedByte, kUnsignedShort, kUnsignedInt},
                 "a SCALAR accessor of unsigned bytes, shorts or ints");
  const Elements e = elements(ctx, accessor, use);
  const int type = ctx.model.accessors[std::size_t(accessor)].componentType;
  std::vector<std::uint32_t> out(e.count);
  for (std::size_t i = 0; i < e.count; ++i) out[i] = read_index(e.at(i), type);
  return out;
}

} // namespace irad::gltf
