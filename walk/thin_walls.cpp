#include "walk/thin_walls.h"

#include "core/util/parallel_rows.h"

#include <algorithm>
#include <atomic>
#include <optional>
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

// The least gap behind the triangles [begin, end) to the first back-turned surface, in scene
// units; `reach` when there is none within it. Two rays from each centroid c along -n: from
// c + h n (h = 2 ray epsilons) over [0, 2h], whose first hit is t itself or a face coincident
// with it (opposite winding: gap 0; Embree returns either at the tie, and the pair's other
// triangle asks too); then from c over (epsilon, reach] for the faces behind. The first ray stops
// at 2h because only a hit within h of t's plane counts: a short segment visits only the BVH
// nodes around c. Neighbouring triangles' rays run close and alike, so they go as packets.
float least_gap_behind(const Scene& scene, const RayScene& rays, std::size_t begin, std::size_t end,
                       float reach) {
  const float h = 2.0f * rays.epsilon();
  std::vector<RaySegment> near, behind;
  std::vector<std::uint32_t> from;
  for (std::size_t t = begin; t < end; ++t) {
    if (scene.material_of(t).alpha_mode != AlphaMode::Opaque) continue;
    const glm::vec3 n = front_normal(scene, t);
    if (n == glm::vec3(0.0f)) continue;
    const glm::uvec3 v = scene.triangles[t];
    const glm::vec3 c = (scene.positions[v.x] + scene.positions[v.y] + scene.positions[v.z]) / 3.0f;
    near.push_back({c + h * n, -n, 0.0f, 2.0f * h});
    behind.push_back({c, -n, rays.epsilon(), reach});
    from.push_back(static_cast<std::uint32_t>(t));
  }
  std::vector<std::optional<RayHit>> hits(near.size());
  rays.intersect(near.data(), near.size(), hits.data());
  for (std::size_t i = 0; i < near.size(); ++i)
    if (hits[i] && hits[i]->triangle != from[i] && back_towards(scene, *hits[i], near[i].direction))
      return 0.0f;
  rays.intersect(behind.data(), behind.size(), hits.data());
  float least = reach;
  for (std::size_t i = 0; i < behind.size(); ++i)
    if (hits[i] && back_towards(scene, *hits[i], behind[i].direction))
      least = std::min(least, hits[i]->t);
  return least;
}

} // namespace

bool has_zero_wall(const Scene& scene) {
  for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
    const Material& m = scene.material_of(t);
    if (m.alpha_mode == AlphaMode::Opaque && two_sided(m)) return true;
  }
  return false;
}

float thinnest_wall(const Scene& scene, const RayScene& rays, float up_to, unsigned threads) {
  const float diagonal = scene.bounds.diagonal();
  if (diagonal <= 0.0f || up_to <= 0.0f) return up_to;
  if (has_zero_wall(scene)) return 0.0f;
  // The least gap so far, shared by all rows: each row's rays reach only as far as it, which is
  // exact (a gap beyond the least found cannot be the least) and shortens the rays after the
  // first walls.
  std::atomic<float> least(up_to * diagonal);
  constexpr std::size_t kRow = 256;
  const std::size_t count = scene.triangle_count();
  const int rows = static_cast<int>((count + kRow - 1) / kRow);
  parallel_rows(rows, threads, [&](int row) {
    float g = least.load(std::memory_order_relaxed);
    if (g <= 0.0f) return;
    const std::size_t begin = static_cast<std::size_t>(row) * kRow;
    const float gap = least_gap_behind(scene, rays, begin, std::min(count, begin + kRow), g);
    while (gap < g && !least.compare_exchange_weak(g, gap, std::memory_order_relaxed)) {
    }
  });
  const float gap = least.load();
  return std::min(up_to, gap / diagonal);
}

} // namespace irad
