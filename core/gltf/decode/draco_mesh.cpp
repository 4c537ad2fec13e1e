// KHR_draco_mesh_compression through Debian's libdraco (1.5). Draco's own messages never pass
// through; every index it hands back is checked against the sizes it reports, so that corrupt
// data give a CodecError instead of a read out of bounds.
#include "core/gltf/decode/codecs.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <type_traits>

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>
#include <fmt/format.h>

namespace irad::gltf {

struct DracoMesh::Impl {
  std::unique_ptr<draco::Mesh> mesh;
};

namespace {

constexpr int kMaxComponents = 16; // MAT4

// Decodes a triangle mesh, or throws. Library exceptions (allocation failures on absurd sizes)
// become CodecErrors too.
std::unique_ptr<draco::Mesh> decode_mesh(const unsigned char* data, std::size_t size) {
  if (!data || size == 0) throw CodecError("the Draco data are empty");
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(data), size);
  try {
    auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
    if (!type.ok()) throw CodecError("the Draco data do not decode (corrupt header)");
    if (type.value() != draco::TRIANGULAR_MESH) {
      throw CodecError("the Draco data hold a point cloud, not a triangle mesh");
    }
    draco::Decoder decoder;
    auto mesh = decoder.DecodeMeshFromBuffer(&buffer);
    if (!mesh.ok() || !mesh.value()) {
      throw CodecError("the Draco mesh does not decode (corrupt or unsupported data)");
    }
    return std::move(mesh).value();
  } catch (const CodecError&) {
    throw;
  } catch (const std::exception&) {
    throw CodecError("the Draco mesh does not decode (out of memory)");
  }
}

// The value index of `point`, checked against the attribute's sizes.
draco::AttributeValueIndex value_index(const draco::PointAttribute& attribute,
                                       draco::PointIndex point) {
  if (!attribute.is_mapping_identity() && point.value() >= attribute.indices_map_size()) {
    throw CodecError("the Draco attribute maps fewer points than the mesh has");
  }
  const draco::AttributeValueIndex index = attribute.mapped_index(point);
  if (index.value() >= attribute.size()) {
    throw CodecError("the Draco attribute refers to a value it does not hold");
  }
  return index;
}

bool is_float(draco::DataType type) {
  return type == draco::DT_FLOAT32 || type == draco::DT_FLOAT64;
}

// A float to integer component type T, as glTF defines it: normalized values are clamped to
// [0, 1] (unsigned) or [-1, 1] (signed) and scaled to T's range; others are rounded and must fit.
template <typename T>
T float_to_integer(float value, bool normalized) {
  if (!std::isfinite(value)) throw CodecError("a Draco attribute value is not finite");
  constexpr double lowest = std::is_signed_v<T> ? -1.0 : 0.0;
  constexpr double max = double(std::numeric_limits<T>::max());
  double v = double(value);
  if (normalized) {
    v = std::round(std::clamp(v, lowest, 1.0) * max);
  } else {
    v = std::round(v);
    if (v < double(std::numeric_limits<T>::lowest()) || v > max) {
      throw CodecError("a Draco attribute value does not fit its accessor's component type");
    }
  }
  return static_cast<T>(v);
}

// One point's components as T (the accessor's component type).
template <typename T>
void convert_point(const draco::PointAttribute& attribute, draco::AttributeValueIndex index,
                   int components, bool normalized, T* out) {
  const auto n = static_cast<std::int8_t>(components);
  bool ok = true;
  if constexpr (std::is_floating_point_v<T>) {
    ok = attribute.ConvertValue<T>(index, n, out);
  } else if (is_float(attribute.data_type())) {
    float values[kMaxComponents];
    ok = attribute.ConvertValue<float>(index, n, values);
    for (int c = 0; ok && c < components; ++c) out[c] = float_to_integer<T>(values[c], normalized);
  } else {
    ok = attribute.ConvertValue<T>(index, n, out); // integer to integer, range-checked by Draco
  }
  if (!ok) throw CodecError("a Draco attribute value does not convert to its accessor's type");
}

template <typename T>
std::vector<unsigned char> convert(const draco::PointAttribute& attribute, std::size_t points,
                                   int components, bool normalized) {
  std::vector<unsigned char> out(points * std::size_t(components) * sizeof(T));
  T values[kMaxComponents];
  for (std::size_t p = 0; p < points; ++p) {
    const auto index = value_index(attribute, draco::PointIndex(std::uint32_t(p)));
    convert_point(attribute, index, components, normalized, values);
    std::memcpy(out.data() + p * std::size_t(components) * sizeof(T), values,
                std::size_t(components) * sizeof(T));
  }
  return out;
}

} // namespace

DracoMesh::DracoMesh(const unsigned char* data, std::size_t size)
    : impl_(new Impl{decode_mesh(data, size)}) {}

DracoMesh::~DracoMesh() {
  delete impl_;
}

DracoMesh::DracoMesh(DracoMesh&& other) noexcept : impl_(other.impl_) {
  other.impl_ = nullptr;
}

DracoMesh& DracoMesh::operator=(DracoMesh&& other) noexcept {
  if (this != &other) {
    delete impl_;
    impl_ = other.impl_;
    other.impl_ = nullptr;
  }
  return *this;
}

std::size_t DracoMesh::vertex_count() const {
  if (!impl_) throw CodecError("a moved-from Draco mesh");
  return impl_->mesh->num_points();
}

std::vector<std::uint32_t> DracoMesh::indices() const {
  const std::size_t points = vertex_count();
  const draco::Mesh& mesh = *impl_->mesh;
  std::vector<std::uint32_t> out;
  out.reserve(std::size_t(mesh.num_faces()) * 3);
  for (std::uint32_t f = 0; f < mesh.num_faces(); ++f) {
    for (const draco::PointIndex& corner : mesh.face(draco::FaceIndex(f))) {
      if (corner.value() >= points) throw CodecError("a Draco face refers to a missing vertex");
      out.push_back(corner.value());
    }
  }
  return out;
}

std::vector<unsigned char> DracoMesh::attribute(int id, int component_type, int components,
                                                bool normalized) const {
  const std::size_t points = vertex_count();
  if (id < 0) throw CodecError(fmt::format("Draco attribute id {} is negative", id));
  const draco::PointAttribute* attribute =
      impl_->mesh->GetAttributeByUniqueId(static_cast<std::uint32_t>(id));
  if (!attribute) throw CodecError(fmt::format("the Draco mesh has no attribute with id {}", id));
  if ((components < 1 || components > 4) && components != kMaxComponents) {
    throw CodecError(fmt::format("{} components per element (1..4 or 16 expected)", components));
  }
  if (attribute->num_components() != components) {
    throw CodecError(fmt::format("Draco attribute {} has {} components, its accessor {}", id,
                                 attribute->num_components(), components));
  }
  switch (component_type) {
  case 5120:
    return convert<std::int8_t>(*attribute, points, components, normalized);
  case 5121:
    return convert<std::uint8_t>(*attribute, points, components, normalized);
  case 5122:
    return convert<std::int16_t>(*attribute, points, components, normalized);
  case 5123:
    return convert<std::uint16_t>(*attribute, points, components, normalized);
  case 5125:
    return convert<std::uint32_t>(*attribute, points, components, normalized);
  case 5126:
    return convert<float>(*attribute, points, components, false);
  default:
    break;
  }
  throw CodecError(fmt::format("component type {} is not a glTF accessor type", component_type));
}

} // namespace irad::gltf
