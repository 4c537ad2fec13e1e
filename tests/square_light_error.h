#pragma once
// The raster against Lambert's formula for a square light over a plane (design.md section 3):
// shared by tests/test_raster_analytic.cpp and tests/test_batched.cpp.
#include "core/camera/view.h"
#include "core/scene/scene_builder.h"
#include "raster/raster_renderer.h"
#include "walk/vpls/quasi_random_walk.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <numbers>

namespace irad {

// World-space ray through the centre of pixel (px, py) (row 0 at the top).
inline void pixel_ray(const View& view, int px, int py, glm::dvec3& origin, glm::dvec3& dir) {
  const glm::dmat4 inv = glm::inverse(glm::dmat4(view.projection) * glm::dmat4(view.view));
  const double nx = (px + 0.5) / view.width * 2.0 - 1.0;
  const double ny = 1.0 - (py + 0.5) / view.height * 2.0;
  glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0);
  glm::dvec4 b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
  origin = glm::dvec3(a) / a.w;
  dir = glm::normalize(glm::dvec3(b) / b.w - origin);
}

// A 1 m square light of radiance 1 at 1 m over a 6 m grey plane (albedo 0.5), seen obliquely.
// Expected pixel: rho E(x) / pi, with E from Lambert's formula; the light's albedo is 0, so only
// direct light reaches the plane. Error sources: N-point quadrature over the light, shadow-map
// bias on the plane itself; the clamp distance (0.05 * 6.2 m = 0.31 m) is below the light's
// height, so the clamp removes nothing.
// Relative error of the raster against Lambert's formula over the visible plane.
struct LambertError {
  double rel_rms = 0.0, max_rel = 0.0;
  int count = 0;
};

// batch: RasterOptions::batch (1: one pass per VPL).
inline LambertError square_light_error(int interleave, int shadow_resolution,
                                       int batch = RasterOptions{}.batch) {
  Log log([](const std::string&) {});
  const float albedo = 0.5f, height = 1.0f, side = 1.0f;
  Scene scene = square_light_over_plane(side, height, 1.0f, 6.0f, albedo);
  scene.cameras.push_back(look_at({0.0f, -3.2f, 2.6f}, {0.0f, 0.0f, 0.2f}, {0, 0, 1}, 0.9f));
  const RayScene rays(scene);
  const VplSet vpls = quasi_random_walk(scene, rays, {1024, 64}, log);
  RasterOptions options{shadow_resolution, 0.05f};
  options.interleave = interleave;
  options.batch = batch;
  RasterRenderer raster(scene, options);
  const View view = make_view(scene.cameras[0], scene.bounds, 160, 120);
  const Image image = raster.render(view, vpls);

  const double l = 0.5 * side;
  const std::vector<glm::dvec3> light = {
      {-l, -l, height}, {-l, l, height}, {l, l, height}, {l, -l, height}};
  double sum_sq = 0.0;
  LambertError e;
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      glm::dvec3 o, d;
      pixel_ray(view, x, y, o, d);
      if (d.z >= 0.0) continue;
      // Skip pixels that see the light (or pass within a pixel of its edge) before the plane.
      const double t_light = (height - o.z) / d.z;
      const glm::dvec3 at_light = o + t_light * d;
      if (t_light > 0 && std::abs(at_light.x) < l + 0.02 && std::abs(at_light.y) < l + 0.02)
        continue;
      const glm::dvec3 p = o + (-o.z / d.z) * d;
      if (std::abs(p.x) > 2.9 || std::abs(p.y) > 2.9) continue; // plane edges
      const double expected =
          albedo / std::numbers::pi * polygon_irradiance(light, p, {0, 0, 1}, 1.0);
      const double got = image.at(x, y).r;
      EXPECT_TRUE(std::isfinite(got));
      const double rel = (got - expected) / expected;
      sum_sq += rel * rel;
      e.max_rel = std::max(e.max_rel, std::abs(rel));
      ++e.count;
    }
  e.rel_rms = std::sqrt(sum_sq / e.count);
  std::printf("square light over plane (interleave %d, batch %d): %d pixels, relative RMS %.5f,"
              " max %.5f\n",
              interleave, batch, e.count, e.rel_rms, e.max_rel);
  return e;
}

} // namespace irad
