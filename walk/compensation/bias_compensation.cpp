#include "walk/compensation/bias_compensation.h"

#include "core/lights/clamp_field.h"
#include "core/lights/light_sampler.h"
#include "core/sampling/rng.h"
#include "core/util/parallel_rows.h"
#include "walk/estimators/vpl_gather.h"

#include <cmath>
#include <limits>

namespace irad {

namespace {

struct Residual {
  const Scene& scene;
  const RayScene& rays;
  const VplSet& vpls;
  float dmin; // the global clamp (world units); the local one is vpls.clamp_field
  float eps;
  int max_depth;

  // The largest clamp distance anywhere: the gather ray's reach.
  float reach() const { return vpls.clamp_field ? vpls.clamp_field->cap() : dmin; }
  // d(y): the clamp distance of light leaving y.
  float clamp_at(const glm::vec3& y) const {
    return vpls.clamp_field ? vpls.clamp_field->at(y) : dmin;
  }

  // One-sample estimate of R(x) (see the header).
  glm::vec3 operator()(const ShadingPoint& x, Pcg32& rng, int depth) const {
    if (depth >= max_depth) return glm::vec3(0.0f);
    const double u = rng.next_double(), v = rng.next_double();
    const glm::vec3 w = cosine_direction(x.normal, u, v);
    if (glm::dot(w, x.geometric) <= 0.0f) return glm::vec3(0.0f);
    const glm::vec3 origin = x.position + eps * x.geometric;
    const auto hit = rays.intersect(origin, w, 0.0f, reach());
    if (!hit) return glm::vec3(0.0f);
    const float d = hit->t;
    const ShadingPoint y = shading_point(scene, *hit, origin, w);
    const float dy = clamp_at(y.position);
    const float weight = dy > 0.0f ? 1.0f - d * d / (dy * dy) : 0.0f;
    if (weight <= 0.0f) return glm::vec3(0.0f);
    const glm::vec3 radiance =
        y.emission + gather_vpls(rays, y, vpls, dmin, eps) + (*this)(y, rng, depth + 1);
    return x.albedo * weight * radiance;
  }
};

float mean3(const glm::vec3& c) {
  return (c.x + c.y + c.z) / 3.0f;
}

} // namespace

Image clamp_residual(const Scene& scene, const RayScene& rays, const View& view, const VplSet& vpls,
                     const BiasCompensationOptions& options) {
  const float dmin = options.clamp * scene.bounds.diagonal();
  const Residual residual{scene, rays, vpls, dmin, rays.epsilon(), options.max_depth};
  Image image(view.width, view.height);
  const std::uint64_t seed = mix64(options.seed ^ 0x62696173ULL);
  parallel_rows(view.height, options.threads, [&](int y) {
    for (int x = 0; x < view.width; ++x) {
      glm::vec3 sum(0.0f);
      const CameraRay ray = pixel_ray(view, x, y);
      const glm::vec3 dir = ray.direction;
      const auto hit = rays.intersect(ray.origin, dir, view.znear, 2.0f * view.zfar);
      if (hit && residual.reach() > 0.0f && options.samples > 0) {
        const ShadingPoint p = shading_point(scene, *hit, ray.origin, dir);
        Pcg32 rng(mix64(seed ^ (static_cast<std::uint64_t>(y) * view.width + x)), 0);
        for (std::uint32_t s = 0; s < options.samples; ++s) sum += residual(p, rng, 0);
        sum /= static_cast<float>(options.samples);
      }
      image.at(x, y) = glm::vec4(sum, 1.0f);
    }
  });
  return image;
}

double clamped_fraction(const Scene& scene, const RayScene& rays, const View& view,
                        const VplSet& vpls, float clamp, int grid, std::uint32_t samples,
                        unsigned threads) {
  const float dmin = clamp * scene.bounds.diagonal();
  const Residual residual{scene, rays, vpls, dmin, rays.epsilon(), 16};
  if (residual.reach() <= 0.0f) return 0.0;
  const int nx = std::min(grid, view.width), ny = std::min(grid, view.height);
  std::vector<double> kept_row(std::size_t(ny), 0.0), removed_row(std::size_t(ny), 0.0);
  parallel_rows(ny, threads, [&](int j) {
    double& kept = kept_row[std::size_t(j)];
    double& removed = removed_row[std::size_t(j)];
    for (int i = 0; i < nx; ++i) {
      const int px = (2 * i + 1) * view.width / (2 * nx);
      const int py = (2 * j + 1) * view.height / (2 * ny);
      const CameraRay ray = pixel_ray(view, px, py);
      const glm::vec3 dir = ray.direction;
      const auto hit = rays.intersect(ray.origin, dir, view.znear, 2.0f * view.zfar);
      if (!hit) continue;
      const ShadingPoint p = shading_point(scene, *hit, ray.origin, dir);
      Pcg32 rng(mix64(static_cast<std::uint64_t>(py) * view.width + px), 1);
      glm::vec3 r(0.0f);
      for (std::uint32_t s = 0; s < samples; ++s) r += residual(p, rng, 0);
      removed += mean3(r) / static_cast<float>(samples);
      kept += mean3(gather_vpls(rays, p, vpls, dmin, rays.epsilon()));
    }
  });
  double kept = 0.0, removed = 0.0; // summed in row order: independent of the threads
  for (int j = 0; j < ny; ++j) {
    kept += kept_row[std::size_t(j)];
    removed += removed_row[std::size_t(j)];
  }
  return kept + removed > 0.0 ? removed / (kept + removed) : 0.0;
}

} // namespace irad
