#pragma once
// A finely tessellated curved occluder for the shadow level-of-detail studies
// (apps/bench/bench.cpp, tests/test_shadow_lod.cpp): a UV sphere with shared vertices and smooth
// normals.
#include "core/scene/scene.h"

#include <cstdint>
#include <glm/glm.hpp>

namespace irad {

// Adds a sphere of `radius` around `centre` facing outward (counter-clockwise seen from
// outside): `rings` rings of latitude (>= 2), 2 * rings segments of longitude, so
// 4 * rings * (rings - 1) triangles (the pole rings are fans). Returns the triangles added.
// Call finish() afterwards for the bounds.
std::size_t add_sphere(Scene& scene, const glm::vec3& centre, float radius, int rings,
                       std::uint32_t material);

// The rings for about `triangles` triangles: 4 r (r - 1) >= triangles.
int sphere_rings_for(std::size_t triangles);

} // namespace irad
