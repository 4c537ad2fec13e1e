#pragma once
// Scenes built in code: the small vocabulary (quads, materials, a look-at camera, bounds) from
// which the analytic scenes (core/scene/analytic_scenes.h) and the tests assemble their geometry,
// and Lambert's polygon formula (design.md section 3).
//
// The builders here keep the invariants of a loaded scene (core/gltf/loader.h) as long as their
// inputs are valid: unit normals, no zero-area triangles, bounds set by finish(). Invalid inputs
// (non-positive sizes, albedo outside [0, 1], negative radiance, degenerate quads or cameras)
// throw irad::Error.
#include "core/scene/scene.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace irad {

// Adds a planar quad p0 p1 p2 p3 (counter-clockwise seen from its front) as the two triangles
// (p0 p1 p2) and (p0 p2 p3), with the flat normal normalize((p1 - p0) x (p2 - p0)) and material
// `material`. Throws when either triangle has zero area.
void add_quad(Scene& scene, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
              const glm::vec3& p3, std::uint32_t material);
// Appends a material named "materialK" (K its index) and returns K.
std::uint32_t add_material(Scene& scene, const glm::vec3& albedo, const glm::vec3& emission = {},
                           bool double_sided = false);
// A pinhole camera named "test" at `eye` looking at `target`, `up` giving the image's up
// direction; yfov in radians. Throws when eye == target or up is parallel to the view direction.
Camera look_at(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up, float yfov);
// Recomputes Scene::bounds.
void finish(Scene& scene);
// Throws Error(builder, name, ...) unless value is finite and > 0.
void require_positive(const char* builder, const char* name, double value);

// A square light of side `side` and radiance `radiance`, centred at height `height` above the
// plane z = 0 (a square of side `plane_side` centred at the origin, albedo `albedo`, facing +z),
// facing down; light albedo 0, so the image is direct light only. No camera.
Scene square_light_over_plane(float side, float height, float radiance, float plane_side,
                              float albedo);

// Irradiance at x (normal n) from a Lambertian polygon of radiance L (Lambert's formula):
// E = (L/2) |sum_i acos(r_i . r_{i+1}) n . normalize(r_i x r_{i+1})|, r_i = normalize(v_i - x).
// Valid when the whole polygon lies above x's tangent plane and faces x.
double polygon_irradiance(const std::vector<glm::dvec3>& polygon, const glm::dvec3& x,
                          const glm::dvec3& n, double radiance);

// A closed axis-aligned box [0,size]^3 whose walls (facing inward) have albedo `albedo`, with an
// emitting square patch of side `patch` and radiance `radiance` just below the ceiling (y = size),
// facing down; the patch has the walls' albedo. No particle can leave it. No camera.
// albedo may be 1 here (tests of the walk's depth cap use it).
Scene closed_box(float size, float albedo, float patch, float radiance);

} // namespace irad

namespace irad {
// Splits every triangle into 4 (edge midpoints), `levels` times: 4^levels times the triangles,
// the same surfaces, materials and lighting (normals and uvs interpolated). For scaling tests.
void subdivide(Scene& scene, int levels);
} // namespace irad
