#include "core/mesh/sphere_mesh.h"

#include "core/util/error.h"

#include <cmath>

namespace irad {

std::size_t add_sphere(Scene& scene, const glm::vec3& centre, float radius, int rings,
                       std::uint32_t material) {
  if (rings < 2 || !(radius > 0.0f)) throw Error("", "sphere", "needs rings >= 2, radius > 0");
  const auto first = static_cast<std::uint32_t>(scene.positions.size());
  const int segments = 2 * rings;
  const auto add_vertex = [&](const glm::vec3& n) {
    scene.positions.push_back(centre + radius * n);
    scene.normals.push_back(n);
    if (!scene.uvs.empty()) scene.uvs.emplace_back(0.0f);
    if (!scene.uvs1.empty()) scene.uvs1.emplace_back(0.0f);
    if (!scene.colors.empty()) scene.colors.emplace_back(1.0f);
  };
  const double pi = 3.14159265358979323846;
  add_vertex({0.0f, 1.0f, 0.0f}); // north pole: vertex first
  for (int i = 1; i < rings; ++i) {
    const double theta = pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2.0 * pi * j / segments;
      add_vertex(glm::vec3(glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                      -std::sin(theta) * std::sin(phi))));
    }
  }
  add_vertex({0.0f, -1.0f, 0.0f}); // south pole
  const std::uint32_t south = static_cast<std::uint32_t>(scene.positions.size()) - 1;
  const auto at = [&](int i, int j) { // ring i in 1..rings-1
    return first + 1 + static_cast<std::uint32_t>((i - 1) * segments + (j % segments));
  };
  const std::size_t before = scene.triangles.size();
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    scene.triangles.emplace_back(a, b, c);
    scene.triangle_material.push_back(material);
  };
  // phi runs counter-clockwise seen from +y; theta downward.
  for (int j = 0; j < segments; ++j) add(first, at(1, j), at(1, j + 1));
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      add(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      add(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  for (int j = 0; j < segments; ++j) add(at(rings - 1, j), south, at(rings - 1, j + 1));
  return scene.triangles.size() - before;
}

int sphere_rings_for(std::size_t triangles) {
  int r = 2;
  while (4.0 * r * (r - 1) < static_cast<double>(triangles)) ++r;
  return r;
}

} // namespace irad
