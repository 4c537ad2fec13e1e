#pragma once
// Internal to the glTF loader: bounds-checked reading of accessors.
// Every accessor is validated before a byte is read: its bufferView and buffer indices, the
// bufferView's range within the buffer's data, byteStride >= element size, and
// byteOffset + stride (count - 1) + element size <= bufferView.byteLength. Sparse accessors are
// supported (densified; sparse indices must increase strictly and lie below count). count may
// not exceed 3 x limits.max_triangles. Errors name "accessors[N]",
// "bufferViews[N]", or `use` (the referring element) for a bad accessor index.
#include "core/gltf/context.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace irad::gltf {

// Float VEC3 accessor (POSITION, NORMAL).
std::vector<glm::vec3> read_vec3(const Context& ctx, int accessor, const std::string& use);
// VEC2 accessor of floats or normalized unsigned bytes/shorts (TEXCOORD_0), as floats.
std::vector<glm::vec2> read_texcoords(const Context& ctx, int accessor, const std::string& use);
// Animation sampler data as vec4s (unused components 0): `type` TINYGLTF_TYPE_SCALAR (input
// times) or VEC3 (translation, scale) of floats, or VEC4 (rotation) of floats or normalized
// integers (signed c / (2^(bits-1) - 1) clamped to -1, unsigned c / (2^bits - 1)). Fails on
// non-finite values.
std::vector<glm::vec4> read_animation_values(const Context& ctx, int accessor,
                                             const std::string& use, int type);
// SCALAR accessor of unsigned bytes, shorts or ints (indices).
std::vector<std::uint32_t> read_indices(const Context& ctx, int accessor, const std::string& use);

} // namespace irad::gltf
