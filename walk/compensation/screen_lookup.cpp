#include "walk/compensation/screen_lookup.h"

#include "core/util/parallel_rows.h"

#include <cmath>

namespace irad {

glm::vec3 camera_to(const ShadingPoint& y, const glm::vec3& toward) {
  if (!y.glossy) return glm::vec3(1.0f);
  const Brdf& b = y.glossy->brdf;
  const glm::vec3 to_camera = b.albedo(y.glossy->wo), to_there = b.albedo(toward);
  glm::vec3 out(0.0f);
  for (int ch = 0; ch < 3; ++ch)
    if (to_camera[ch] > 0.0f) out[ch] = to_there[ch] / to_camera[ch];
  return out;
}

ScreenLookup::ScreenLookup(const Scene& scene, const RayScene& rays, const View& view,
                           unsigned threads)
    : rays_(&rays), view_(&view), eps_(rays.epsilon()),
      centres_(std::size_t(view.width) * std::size_t(view.height)) {
  parallel_rows(view.height, threads, [&](int y) {
    for (int x = 0; x < view.width; ++x)
      centres_[std::size_t(y) * view.width + x] = visible_point(scene, rays, view, x, y);
  });
}

int ScreenLookup::camera_pixel(const glm::vec3& y, const glm::vec3& n) const {
  const View& view = *view_;
  const float eps = eps_;
  const RayScene& rays = *rays_;
  const glm::vec4 clip = view.projection * view.view * glm::vec4(y, 1.0f);
  if (!(clip.w > 0.0f)) return -1;
  const float px = (clip.x / clip.w * 0.5f + 0.5f) * static_cast<float>(view.width);
  const float py = (0.5f - clip.y / clip.w * 0.5f) * static_cast<float>(view.height);
  if (!(px >= 0.0f && py >= 0.0f && px < float(view.width) && py < float(view.height))) return -1;
  glm::vec3 to_eye;
  float distance;
  if (view.orthographic) {
    to_eye = -view.forward;
    distance = glm::dot(y - view.eye, view.forward);
  } else {
    to_eye = view.eye - y;
    distance = glm::length(to_eye);
    to_eye /= distance;
  }
  if (!(glm::dot(n, to_eye) > 0.0f) || !(distance > 2.0f * eps)) return -1;
  if (rays.occluded(y + eps * n, to_eye, 0.0f, distance - 2.0f * eps)) return -1;
  // A pixel's height in world units at y's depth (P[1][1] = cot(yfov / 2), or 1 / ymag).
  const float depth = view.orthographic ? 1.0f : glm::dot(y - view.eye, view.forward);
  const float footprint = 2.0f * depth / (static_cast<float>(view.height) * view.projection[1][1]);
  const int ix = static_cast<int>(px), iy = static_cast<int>(py);
  int best = -1;
  float best_d2 = 0.0f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int qx = ix + dx, qy = iy + dy;
      if (qx < 0 || qy < 0 || qx >= view.width || qy >= view.height) continue;
      const float ex = float(qx) + 0.5f - px, ey = float(qy) + 0.5f - py;
      const float d2 = (dx == 0 && dy == 0) ? -1.0f : ex * ex + ey * ey; // y's own pixel first
      if (best >= 0 && d2 >= best_d2) continue;
      const int i = qy * view.width + qx;
      if (!same_surface(centres_[std::size_t(i)], y, n, footprint)) continue;
      best = i;
      best_d2 = d2;
    }
  return best;
}

bool ScreenLookup::same_surface(const PixelCentre& centre, const glm::vec3& y, const glm::vec3& n,
                                float footprint) {
  return centre && glm::dot(centre->geometric, n) > 0.95f &&
         std::abs(glm::dot(n, centre->position - y)) <= 0.5f * footprint;
}

} // namespace irad
