#pragma once
// Internal to the glTF loader: the compressed-geometry decoders, KHR_draco_mesh_compression
// (Debian's libdraco) and EXT_meshopt_compression (Debian's libmeshoptimizer). Both throw
// CodecError with one line in irad's words (no library text passes through raw); the loader
// prefixes the file and the bufferView.
#include <cstddef>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace irad::gltf {

class CodecError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// EXT_meshopt_compression: decodes `count` elements of `byte_stride` bytes from the compressed
// bytes. mode: "ATTRIBUTES", "TRIANGLES" or "INDICES"; filter: "NONE", "OCTAHEDRAL",
// "QUATERNION" or "EXPONENTIAL" (applied after decoding, in place). Returns count * byte_stride
// bytes. Fails on an unknown mode or filter, a stride the mode does not allow (ATTRIBUTES: a
// multiple of 4 up to 256; TRIANGLES and INDICES: 2 or 4), a TRIANGLES count that is not a
// multiple of 3, a filter outside ATTRIBUTES (OCTAHEDRAL: stride 4 or 8; QUATERNION: 8), or
// corrupt or truncated data. count 0 gives no bytes without reading `data`.
std::vector<unsigned char> decode_meshopt(const unsigned char* data, std::size_t size,
                                          std::size_t count, std::size_t byte_stride,
                                          std::string_view mode, std::string_view filter);

// A KHR_draco_mesh_compression bufferView, decoded.
class DracoMesh {
public:
  // Decodes a Draco triangle mesh; fails on point clouds and corrupt data.
  DracoMesh(const unsigned char* data, std::size_t size);
  ~DracoMesh();
  DracoMesh(DracoMesh&&) noexcept;
  DracoMesh& operator=(DracoMesh&&) noexcept;

  std::size_t vertex_count() const;
  // Triangle corner indices (3 per face).
  std::vector<std::uint32_t> indices() const;
  // The attribute with Draco unique id `id`, converted to the glTF accessor layout that refers to
  // it: `components` components (1..4, or 16 for MAT4) of glTF componentType `component_type`
  // (5120..5126), tightly packed, one element per vertex. Values are dequantized by Draco and
  // converted as the glTF accessor's type says (normalized integers scaled to their range when
  // `normalized`: floats clamped to [0, 1] or [-1, 1], times the type's maximum, rounded;
  // integer to integer: the values as they are, which must fit). Fails when no attribute has
  // that id, when its component count is not `components`, or when a value does not convert.
  // (A moved-from DracoMesh throws CodecError from every member.)
  std::vector<unsigned char> attribute(int id, int component_type, int components,
                                       bool normalized) const;

private:
  struct Impl;
  Impl* impl_;
};

} // namespace irad::gltf
