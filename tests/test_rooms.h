#pragma once
// Closed rooms for the leak and occlusion tests (tests/test_hard_cases.cpp,
// tests/test_shadow_lod.cpp, tests/test_shadow_occlusion.cpp).
#include "core/scene.h"
#include "core/scene_builder.h"

#include <glm/glm.hpp>

namespace irad::test_support {

// Six inward-facing quads (counter-clockwise seen from inside) closing the box [lo, hi].
inline void add_room(Scene& s, const glm::vec3& lo, const glm::vec3& hi, std::uint32_t material) {
  const float x0 = lo.x, y0 = lo.y, z0 = lo.z, x1 = hi.x, y1 = hi.y, z1 = hi.z;
  add_quad(s, {x0, y0, z0}, {x0, y0, z1}, {x1, y0, z1}, {x1, y0, z0}, material); // floor, +y
  add_quad(s, {x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}, material); // ceiling, -y
  add_quad(s, {x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}, material); // z0, +z
  add_quad(s, {x0, y0, z1}, {x0, y1, z1}, {x1, y1, z1}, {x1, y0, z1}, material); // z1, -z
  add_quad(s, {x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}, material); // x0, +x
  add_quad(s, {x1, y0, z0}, {x1, y0, z1}, {x1, y1, z1}, {x1, y1, z0}, material); // x1, -x
}

} // namespace irad::test_support
