#pragma once
// A planar mirror polygon (core/scene/mirrors.h): plain data, shared by the VPL list and the scene.
#include <glm/glm.hpp>
#include <vector>

namespace irad {

struct MirrorPolygon {
  static constexpr std::size_t max_triangles = 16;
  glm::vec4 plane{0.0f};            // (n, w): unit normal n, n . x + w = 0 on the plane
  glm::vec3 reflectance{0.0f};      // R = base_color of its material
  std::vector<glm::vec3> triangles; // three corners per triangle, world space
};

} // namespace irad
