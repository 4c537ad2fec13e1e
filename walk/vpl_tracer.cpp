#include "walk/vpl_tracer.h"

#include <atomic>
#include <cmath>
#include <numbers>
#include <thread>
#include <vector>

namespace irad {

namespace {

constexpr float inv_pi = std::numbers::inv_pi_v<float>;

struct Visible {
  glm::vec3 position, normal, albedo, emission;
};

// Primary ray through the centre of pixel (px, py); row 0 at the top, as the raster.
bool primary_hit(const Scene& scene, const RayScene& rays, const View& view, int px, int py,
                 Visible& out) {
  const glm::mat4 inv = glm::inverse(view.projection * view.view);
  const float nx = (static_cast<float>(px) + 0.5f) / static_cast<float>(view.width) * 2.0f - 1.0f;
  const float ny = 1.0f - (static_cast<float>(py) + 0.5f) / static_cast<float>(view.height) * 2.0f;
  const glm::vec4 far = inv * glm::vec4(nx, ny, 1.0f, 1.0f);
  const glm::vec3 dir = glm::normalize(glm::vec3(far) / far.w - view.eye);
  const auto hit = rays.intersect(view.eye, dir, view.znear, view.zfar * 2.0f);
  if (!hit) return false;
  const SurfacePoint sp = surface_at(scene, hit->triangle, hit->bary);
  out.position = view.eye + hit->t * dir;
  const bool front = glm::dot(sp.geometric_normal, dir) < 0.0f;
  out.normal = front ? sp.shading_normal : -sp.shading_normal; // as the raster's gl_FrontFacing
  out.albedo = albedo_at(scene, hit->triangle, hit->bary);
  const Material& m = scene.material_of(hit->triangle);
  out.emission =
      (front || m.double_sided) ? emission_at(scene, hit->triangle, hit->bary) : glm::vec3(0.0f);
  return true;
}

float emission_profile(const Vpl& v, float cos_y) {
  switch (v.kind) {
  case VplKind::Surface:
    return glm::max(cos_y, 0.0f);
  case VplKind::TwoSided:
    return std::abs(cos_y);
  case VplKind::Point:
    return 1.0f;
  case VplKind::Spot:
    return spot_falloff(cos_y, v.cos_inner, v.cos_outer);
  }
  return 0.0f;
}

glm::vec3 shade(const RayScene& rays, const Visible& x, const VplSet& vpls, float dmin2,
                float eps) {
  glm::vec3 sum(0.0f);
  for (const Vpl& v : vpls.vpls) {
    const glm::vec3 d = x.position - v.position;
    const float dist2 = glm::dot(d, d);
    if (!(dist2 > eps * eps)) continue;
    const float dist = std::sqrt(dist2);
    const glm::vec3 w = d / dist;
    const float cos_x = -glm::dot(x.normal, w);
    if (cos_x <= 0.0f) continue;
    const float e = emission_profile(v, glm::dot(v.normal, w));
    if (e <= 0.0f) continue;
    // Shadow ray from the receiver toward the VPL, stopping short of both ends.
    if (rays.occluded(x.position, -w, eps, dist - eps)) continue;
    const float g = e * cos_x / glm::max(dist2, v.clamped() ? dmin2 : 0.0f);
    sum += v.intensity * g;
  }
  return sum * x.albedo * inv_pi;
}

} // namespace

Image trace_vpls(const Scene& scene, const RayScene& rays, const View& view, const VplSet& vpls,
                 const VplTracerOptions& options) {
  Image image(view.width, view.height);
  const float diagonal = scene.bounds.diagonal();
  const float dmin = options.clamp * diagonal;
  const float eps = rays.epsilon();
  std::atomic<int> next_row{0};
  auto work = [&] {
    for (int y = next_row++; y < view.height; y = next_row++)
      for (int x = 0; x < view.width; ++x) {
        Visible v;
        glm::vec3 c(0.0f);
        if (primary_hit(scene, rays, view, x, y, v))
          c = v.emission + shade(rays, v, vpls, dmin * dmin, eps);
        image.at(x, y) = glm::vec4(c, 1.0f);
      }
  };
  unsigned threads = options.threads ? options.threads : std::thread::hardware_concurrency();
  threads = std::max(1u, threads);
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  return image;
}

} // namespace irad
