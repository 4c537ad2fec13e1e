#pragma once
// A convex polyhedron for furnace tests: an octahedron whose faces are split `levels` times into
// four, the new vertices pushed onto the unit sphere (8 * 4^levels flat facets, each with its own
// three vertices and flat normal, counter-clockwise seen from outside, material 0). The
// hemisphere above every facet is open: no point of it sees another.
#include "core/scene/scene.h"

#include <glm/glm.hpp>
#include <utility>
#include <vector>

namespace irad::test {

// Adds triangle (a, b, c), counter-clockwise seen from outside, with its flat normal.
inline void add_facet(Scene& s, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
  const auto base = static_cast<std::uint32_t>(s.positions.size());
  for (const glm::vec3& p : {a, b, c}) {
    s.positions.push_back(p);
    s.normals.push_back(n);
  }
  s.triangles.emplace_back(base, base + 1, base + 2);
  s.triangle_material.push_back(0);
}

inline void add_polyhedron(Scene& s, int levels) {
  struct Tri {
    glm::vec3 a, b, c;
  };
  std::vector<Tri> tris;
  for (const float sx : {1.0f, -1.0f})
    for (const float sy : {1.0f, -1.0f})
      for (const float sz : {1.0f, -1.0f}) {
        Tri t{{sx, 0, 0}, {0, sy, 0}, {0, 0, sz}};
        if (sx * sy * sz < 0.0f) std::swap(t.b, t.c); // counter-clockwise from outside
        tris.push_back(t);
      }
  for (int l = 0; l < levels; ++l) {
    std::vector<Tri> finer;
    for (const Tri& t : tris) {
      const glm::vec3 ab = glm::normalize(t.a + t.b), bc = glm::normalize(t.b + t.c),
                      ca = glm::normalize(t.c + t.a);
      finer.insert(finer.end(), {{t.a, ab, ca}, {ab, t.b, bc}, {ca, bc, t.c}, {ab, bc, ca}});
    }
    tris = std::move(finer);
  }
  for (const Tri& t : tris) add_facet(s, t.a, t.b, t.c);
}

} // namespace irad::test
