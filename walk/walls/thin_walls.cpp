#include "walk/walls/thin_walls.h"

#include "core/util/parallel_rows.h"

#include <algorithm>
#include <atomic>
#include <optional>
#include <vector>

namespace irad {

namespace {

constexpr std::size_t kRow = 256; // triangles a row of the scan

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

// The gap behind triangle t by two rays from its centroid c along -n (h = 2 ray epsilons): from
// c + h n over [0, 2h], whose first hit is t itself or a face coincident with it (opposite
// winding: gap 0; Embree returns either at the tie, and the pair's other triangle asks too); then
// from c over (epsilon, reach] for the faces behind. `reach` when there is none within it.
float gap_by_two_rays(const Scene& scene, const RayScene& rays, std::uint32_t t, const glm::vec3& c,
                      const glm::vec3& n, float reach) {
  const float h = 2.0f * rays.epsilon();
  const std::optional<RayHit> near = rays.intersect(c + h * n, -n, 0.0f, 2.0f * h);
  if (near && near->triangle != t && back_towards(scene, *near, -n)) return 0.0f;
  const std::optional<RayHit> behind = rays.intersect(c, -n, rays.epsilon(), reach);
  return behind && back_towards(scene, *behind, -n) ? behind->t : reach;
}

// The least gap behind the triangles [begin, end) to the first back-turned surface, in scene
// units; `reach` when there is none within it. One ray from each centroid c along -n, from
// c + h n over [0, h + reach], passing through the triangle itself: its first hit at distance d
// is what gap_by_two_rays's two rays find, a back-turned face giving gap 0 within 2h (on t's
// plane) and d - h beyond; but for a front-turned face within epsilon behind t's plane or in
// front of it, which the second of those rays would pass, so those triangles ask them.
// Neighbouring triangles' rays run close and alike, so they go as packets.
float least_gap_behind(const Scene& scene, const RayScene& rays, std::size_t begin, std::size_t end,
                       float reach) {
  const float h = 2.0f * rays.epsilon();
  std::vector<RaySegment> segments;
  std::vector<std::uint32_t> from;
  for (std::size_t t = begin; t < end; ++t) {
    if (scene.material_of(t).alpha_mode != AlphaMode::Opaque) continue;
    const glm::vec3 n = front_normal(scene, t);
    if (n == glm::vec3(0.0f)) continue;
    const glm::uvec3 v = scene.triangles[t];
    const glm::vec3 c = (scene.positions[v.x] + scene.positions[v.y] + scene.positions[v.z]) / 3.0f;
    segments.push_back({c + h * n, -n, 0.0f, h + reach});
    from.push_back(static_cast<std::uint32_t>(t));
  }
  std::vector<std::optional<RayHit>> hits(segments.size());
  rays.intersect_leaving(segments.data(), from.data(), segments.size(), hits.data());
  float least = reach;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const std::optional<RayHit>& hit = hits[i];
    if (!hit) continue;
    const RaySegment& s = segments[i];
    if (back_towards(scene, *hit, s.direction)) {
      least = std::min(least, hit->t <= 2.0f * h ? 0.0f : hit->t - h);
    } else if (hit->t < h + rays.epsilon()) {
      const glm::vec3 c = s.origin + h * s.direction;
      least = std::min(least, gap_by_two_rays(scene, rays, from[i], c, -s.direction, reach));
    }
    if (least <= 0.0f) break;
  }
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

WallScan::WallScan(const Scene& scene, const RayScene& rays, float up_to)
    : scene_(scene), rays_(rays), up_to_(up_to), diagonal_(scene.bounds.diagonal()) {
  // Nothing to trace where the answer is known at once: no rows, complete from the start.
  if (diagonal_ <= 0.0f || up_to_ <= 0.0f) return;
  if (has_zero_wall(scene)) {
    zero_wall_ = true;
    return;
  }
  rows_ = static_cast<int>((scene.triangle_count() + kRow - 1) / kRow);
  least_.store(up_to * diagonal_);
}

void WallScan::work(const std::atomic<bool>* stop) {
  const std::size_t count = scene_.triangle_count();
  for (int row = next_++; row < rows_; row = next_++) {
    if (stop != nullptr && stop->load(std::memory_order_relaxed)) return; // the row is dropped
    float g = least_.load(std::memory_order_relaxed);
    if (g > 0.0f) {
      const std::size_t begin = static_cast<std::size_t>(row) * kRow;
      const float gap = least_gap_behind(scene_, rays_, begin, std::min(count, begin + kRow), g);
      while (gap < g && !least_.compare_exchange_weak(g, gap, std::memory_order_relaxed)) {
      }
    }
    ++done_;
  }
}

float WallScan::result() const {
  if (diagonal_ <= 0.0f || up_to_ <= 0.0f) return up_to_;
  if (zero_wall_) return 0.0f;
  return std::min(up_to_, least_.load() / diagonal_);
}

float thinnest_wall(const Scene& scene, const RayScene& rays, float up_to, unsigned threads) {
  WallScan scan(scene, rays, up_to);
  const auto workers = static_cast<int>(worker_count(threads, scan.rows()));
  if (!scan.complete()) parallel_rows(workers, threads, [&](int) { scan.work(); });
  return scan.result();
}

} // namespace irad
