#pragma once
// Closed rooms for the leak and occlusion tests (tests/test_two_rooms.cpp,
// tests/test_hard_cases.cpp, tests/test_shadow_lod.cpp, tests/test_shadow_occlusion.cpp,
// tests/test_light_budget.cpp).
#include "core/scene/scene.h"
#include "core/scene/scene_builder.h"

#include <cstdint>

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

struct TwoRooms {
  Scene scene;
  Camera in_b;
  Camera in_a;
  float wall_b = 2.002f; // x of room B's wall on the A side, before scaling
};

// Two closed rooms side by side, 2 m each, separated by a double wall `gap` thick (2 mm by
// default); the light is in room A (x in [0, 2]) only, the cameras look at the shared wall from
// inside each room. At k times the size (every coordinate, the cameras with it; radiance is
// unchanged).
inline TwoRooms two_rooms(float k = 1.0f, float gap = 0.002f) {
  TwoRooms r;
  Scene& s = r.scene;
  s.source = "two_rooms";
  const std::uint32_t wall = add_material(s, glm::vec3(0.6f));
  const std::uint32_t light = add_material(s, glm::vec3(0.6f), glm::vec3(5.0f));
  r.wall_b = 2.0f + gap;
  // Room A: quads 0..5, room B: quads 6..11.
  add_room(s, k * glm::vec3(0.0f), k * glm::vec3(2.0f), wall);
  add_room(s, k * glm::vec3(r.wall_b, 0.0f, 0.0f), k * glm::vec3(r.wall_b + 2.0f, 2.0f, 2.0f),
           wall);
  // Ceiling light of room A, facing down, 1 mm below the ceiling.
  add_quad(s, k * glm::vec3(0.7f, 1.999f, 0.7f), k * glm::vec3(1.3f, 1.999f, 0.7f),
           k * glm::vec3(1.3f, 1.999f, 1.3f), k * glm::vec3(0.7f, 1.999f, 1.3f), light);
  finish(s);
  r.in_b = look_at(k * glm::vec3(r.wall_b + 1.948f, 1.05f, 1.03f),
                   k * glm::vec3(r.wall_b, 0.9f, 1.0f), {0, 1, 0}, 1.5f);
  r.in_a =
      look_at(k * glm::vec3(0.05f, 1.05f, 1.03f), k * glm::vec3(2.0f, 0.9f, 1.0f), {0, 1, 0}, 1.5f);
  return r;
}

} // namespace irad::test_support
