#include "walk/thin_walls.h"

#include "core/util/parallel_rows.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>
#include <vector>

namespace irad {

namespace {

bool two_sided(const Material& m) {
  return m.double_sided || m.specular;
}

// The front normal of triangle t (counter-clockwise winding), or 0 for a degenerate one.
glm::vec3 front_normal(const Scene& scene, std::size_t t) {
  const glm::uvec3 v = scene.triangles[t];
  const glm::vec3 c = glm::cross(scene.positions[v.y] - scene.positions[v.x],
                                 scene.positions[v.z] - scene.positions[v.x]);
  const float length = glm::length(c);
  return length > 0.0f ? c / length : glm::vec3(0.0f);
}

// Whether the hit surface turns its back to a ray travelling along `direction`.
bool back_towards(const Scene& scene, const RayHit& hit, const glm::vec3& direction) {
  return glm::dot(front_normal(scene, hit.triangle), direction) > 0.0f;
}

// The gap behind triangle t to the first back-turned surface, in scene units; `reach` when there
// is none within it. Two rays from the centroid c along -n: from c + h n (h = 2 ray epsilons)
// over [0, h + reach], whose first hit is t itself or a face coincident with it (opposite winding:
// gap 0; Embree returns either at the tie, and the pair's other triangle asks too); then from c
// over (epsilon, reach] for the faces behind.
float gap_behind(const Scene& scene, const RayScene& rays, std::size_t t, float reach) {
  const float h = 2.0f * rays.epsilon();
  const glm::vec3 n = front_normal(scene, t);
  if (n == glm::vec3(0.0f)) return reach;
  const glm::uvec3 v = scene.triangles[t];
  const glm::vec3 c = (scene.positions[v.x] + scene.positions[v.y] + scene.positions[v.z]) / 3.0f;
  const auto first = rays.intersect(c + h * n, -n, 0.0f, h + reach);
  if (first && first->triangle != t && std::abs(first->t - h) <= h &&
      back_towards(scene, *first, -n))
    return 0.0f;
  const auto behind = rays.intersect(c, -n, rays.epsilon(), reach);
  if (behind && back_towards(scene, *behind, -n)) return behind->t;
  return reach;
}

} // namespace

float thinnest_wall(const Scene& scene, const RayScene& rays, float up_to, unsigned threads) {
  const float diagonal = scene.bounds.diagonal();
  if (diagonal <= 0.0f || up_to <= 0.0f) return up_to;
  for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
    const Material& m = scene.material_of(t);
    if (m.alpha_mode == AlphaMode::Opaque && two_sided(m)) return 0.0f;
  }
  const float reach = up_to * diagonal;
  // Rows of triangles, each row's least gap on its own (no shared writes).
  constexpr std::size_t kRow = 4096;
  const std::size_t count = scene.triangle_count();
  const int rows = static_cast<int>((count + kRow - 1) / kRow);
  std::vector<float> least(static_cast<std::size_t>(rows), reach);
  parallel_rows(rows, threads, [&](int row) {
    const std::size_t begin = static_cast<std::size_t>(row) * kRow;
    float& g = least[static_cast<std::size_t>(row)];
    for (std::size_t t = begin; t < std::min(count, begin + kRow) && g > 0.0f; ++t)
      if (scene.material_of(t).alpha_mode == AlphaMode::Opaque)
        g = std::min(g, gap_behind(scene, rays, t, g));
  });
  const float gap = least.empty() ? reach : *std::min_element(least.begin(), least.end());
  return std::min(up_to, gap / diagonal);
}

} // namespace irad
