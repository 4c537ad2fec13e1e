#pragma once
// Internal to the glTF loader: a triangle primitive's index list (its indices accessor, a Draco
// decoding, or none: 0 .. n - 1) read, checked and assembled into triangles.
#include "core/gltf/context.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

namespace irad::gltf {

// glTF primitive modes (3.7.2.1); TRIANGLE_FAN is 6.
inline constexpr int kTriangles = 4;
inline constexpr int kTriangleStrip = 5;

// Triangles an index list of n entries gives in `mode` (TRIANGLES, TRIANGLE_STRIP or _FAN).
std::uint64_t triangle_count(int mode, std::size_t n);

// The primitive `p`'s triangles over its n vertices (`draco`'s index list where it has one):
// every index checked below n, and the scene's triangles (`before` so far plus these) within
// --max-triangles, failing with Error(file, where, ...). A TRIANGLES list of whole triangles is
// read straight into them; other lists are read, then assembled (and freed before the caller's
// arrays grow).
std::vector<glm::uvec3> read_triangles(const Context& ctx, const json& p, int mode,
                                       std::optional<std::vector<std::uint32_t>> draco,
                                       std::size_t n, std::size_t before, const std::string& where);

} // namespace irad::gltf
