#pragma once
// Scenes built in code for tests with known answers (design.md section 3).
#include "core/scene.h"

#include <glm/glm.hpp>

namespace irad::test {

// Adds a planar quad p0 p1 p2 p3 (counter-clockwise seen from its front) with one material.
void add_quad(Scene& scene, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
              const glm::vec3& p3, std::uint32_t material);
std::uint32_t add_material(Scene& scene, const glm::vec3& albedo, const glm::vec3& emission = {},
                           bool double_sided = false);
// A pinhole camera at `eye` looking at `target` with y-up (or z-up when up is given).
Camera look_at(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up, float yfov);
// Recomputes Scene::bounds.
void finish(Scene& scene);

// A square light of side `side` and radiance `radiance`, centred at height `height` above the
// plane z = 0 (a square of side `plane_side` with albedo `albedo`), facing down; light albedo 0,
// so the image is direct light only.
Scene square_light_over_plane(float side, float height, float radiance, float plane_side,
                              float albedo);

// Irradiance at x (normal n) from a Lambertian polygon of radiance L (Lambert's formula):
// E = (L/2) |sum_i acos(r_i . r_{i+1}) n . normalize(r_i x r_{i+1})|, r_i = normalize(v_i - x).
double polygon_irradiance(const std::vector<glm::dvec3>& polygon, const glm::dvec3& x,
                          const glm::dvec3& n, double radiance);

} // namespace irad::test

namespace irad::test {
// A closed axis-aligned box [0,size]^3 whose walls (facing inward) have albedo `albedo`, with an
// emitting square patch of side `patch` and radiance `radiance` just below the ceiling, facing
// down. No particle can leave it.
Scene closed_box(float size, float albedo, float patch, float radiance);
} // namespace irad::test
