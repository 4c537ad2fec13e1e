#pragma once
// Internal to the glTF loader: bounds-checked reading of accessors.
// Every accessor is checked before a byte is read: its bufferView and buffer indices, the
// bufferView's range within its buffer's data (EXT_meshopt_compression views are decoded first,
// core/gltf/decode/codecs.h), byteStride >= element size, and byteOffset + stride (count - 1) +
// element size <= bufferView.byteLength. Accessors without a bufferView are zeros (glTF 3.6.2.3);
// sparse accessors are densified (sparse indices must increase strictly and lie below count). Data
// decoded by KHR_draco_mesh_compression replace an accessor's bufferView (Context's
// accessor data). count may not exceed 3 x limits.max_triangles. Errors name "accessors[N]",
// "bufferViews[N]", or `use` (the referring element) for a bad accessor index.
//
// Component conversion (glTF 3.11 and KHR_mesh_quantization): floats as they are; normalized
// integers as c / (2^bits - 1) (unsigned) or max(c / (2^(bits-1) - 1), -1) (signed); other
// integers as their value.
#include "core/gltf/context.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <initializer_list>
#include <vector>

namespace irad::gltf {

// glTF componentType values.
enum ComponentType : int {
  kByte = 5120,
  kUnsignedByte = 5121,
  kShort = 5122,
  kUnsignedShort = 5123,
  kUnsignedInt = 5125,
  kFloat = 5126,
};

// The bytes of bufferViews[view] (decoded when EXT_meshopt_compression), after use() and the
// checks above; `where` names the referring element.
struct ViewBytes {
  const unsigned char* data;
  std::size_t length;
  std::size_t stride; // 0: tightly packed
};
ViewBytes view_bytes(const Context& ctx, std::uint64_t view, const std::string& where);

// The components of accessor `accessor` (as converted above), count x components values, after
// checking that its type is one of `types` ("SCALAR", "VEC2", ... "MAT4") and its componentType
// one of `component_types`. `normalized_only`: integer component types must be normalized.
struct Values {
  std::vector<float> data;
  std::size_t components = 0;
  std::size_t count() const { return components ? data.size() / components : 0; }
};
Values read_values(const Context& ctx, std::uint64_t accessor, const std::string& use,
                   std::initializer_list<const char*> types,
                   std::initializer_list<int> component_types, bool normalized_only = false);

// POSITION-like VEC3 (any component type: KHR_mesh_quantization), as vec3s.
std::vector<glm::vec3> read_vec3(const Context& ctx, std::uint64_t accessor,
                                 const std::string& use);
// VEC2 texture coordinates (float, or byte/short, normalized or not).
std::vector<glm::vec2> read_texcoords(const Context& ctx, std::uint64_t accessor,
                                      const std::string& use);
// COLOR_0: VEC3 or VEC4 of floats or normalized unsigned bytes/shorts, as RGBA (alpha 1 for
// VEC3), clamped to [0, 1].
std::vector<glm::vec4> read_colors(const Context& ctx, std::uint64_t accessor,
                                   const std::string& use);
// Animation sampler data as vec4s (unused components 0): `type` "SCALAR" (input times, floats),
// "VEC3" (translation, scale) or "VEC4" (rotation) of floats or normalized integers. Fails on
// non-finite values.
std::vector<glm::vec4> read_animation_values(const Context& ctx, std::uint64_t accessor,
                                             const std::string& use, const char* type);
// SCALAR accessor of unsigned bytes, shorts or ints (indices, joints' indices).
std::vector<std::uint32_t> read_indices(const Context& ctx, std::uint64_t accessor,
                                        const std::string& use);
// The same values as triples (3k, 3k + 1, 3k + 2) without the list in between: a TRIANGLES
// primitive's triangles (a count not a multiple of 3 drops the last one or two).
std::vector<glm::uvec3> read_index_triples(const Context& ctx, std::uint64_t accessor,
                                           const std::string& use);
// The accessor's count and type without reading data (after use()).
std::size_t accessor_count(const Context& ctx, std::uint64_t accessor, const std::string& use);

// Size in bytes of one component of a glTF component type; 0 for types glTF does not define.
std::size_t component_size(int component_type);
// Components of a glTF accessor type ("SCALAR" 1 ... "MAT4" 16); 0 if unknown.
std::size_t component_count(const std::string& type);

} // namespace irad::gltf
