// The clamp's bias and its compensation (Kollig & Keller 2004) on scenes with closed-form answers:
// the clamp removes light near seams and corners; adding the gathered residual brings it back.
#include "core/camera/view.h"
#include "core/lights/clamp_field.h"
#include "core/scene/analytic_scenes.h"
#include "raster/raster_renderer.h"
#include "walk/compensation/bias_compensation.h"
#include "walk/compensation/screen_compensation.h"
#include "walk/vpls/quasi_random_walk.h"

#include <cmath>
#include <gtest/gtest.h>

namespace irad {
namespace IRAD_UNITY_ID {

struct Means {
  double clamped, compensated, fraction;
  double screen = 0.0;          // compensated on screen (walk/compensation/screen_compensation.h)
  double screen_fallback = 0.0; // its share of gather samples evaluated exactly
};

double mean_green(const Image& image, const Image* residual = nullptr) {
  double sum = 0.0;
  for (std::size_t i = 0; i < image.pixels().size(); ++i)
    sum += image.pixels()[i].g + (residual != nullptr ? residual->pixels()[i].g : 0.0f);
  return sum / static_cast<double>(image.pixels().size());
}

// The clamped raster image and its screen-space compensation; `local`: the VPLs' clamp follows
// the local field (core/lights/clamp_field.h) with `clamp` as its cap.
Means measure_screen(const AnalyticScene& a, float clamp, std::uint32_t paths, int size,
                     bool local) {
  Log log([](const std::string&) {});
  const Scene& s = a.scene;
  const RayScene rays(s);
  VplSet vpls = quasi_random_walk(s, rays, {paths, 64}, log);
  if (local) apply_local_clamp(vpls, s.bounds.diagonal(), {8, 0.5f, clamp, 1e-4f});
  const View view = make_view(s.cameras.at(0), s.bounds, size, size);
  RasterOptions options{128, clamp};
  const Image image = RasterRenderer(s, options).render(view, vpls); // the default: batched, k 4
  ScreenCompensationOptions screen;
  screen.clamp = clamp;
  screen.samples = 16;
  ScreenCompensationStats stats;
  const Image residual = screen_space_residual(s, rays, view, vpls, image, screen, &stats);
  Means m{mean_green(image), 0.0, 0.0};
  m.screen = mean_green(image, &residual);
  m.screen_fallback = double(stats.fallback) / double(std::max<std::uint64_t>(1, stats.in_reach));
  return m;
}

// Mean over the non-emitting pixels (emission seen directly is exact, not an estimate).
Means measure(const AnalyticScene& a, float clamp, std::uint32_t paths, int size) {
  Log log([](const std::string&) {});
  const Scene& s = a.scene;
  const RayScene rays(s);
  const VplSet vpls = quasi_random_walk(s, rays, {paths, 64}, log);
  const View view = make_view(s.cameras.at(0), s.bounds, size, size);
  RasterOptions options{128, clamp};
  options.interleave = 1; // the reference mode: every VPL shades every pixel
  RasterRenderer raster(s, options);
  const Image image = raster.render(view, vpls);
  const Image residual = clamp_residual(s, rays, view, vpls, {clamp, 16, 1, 0, 16});
  double sum = 0.0, sum_c = 0.0;
  for (std::size_t i = 0; i < image.pixels().size(); ++i) {
    sum += image.pixels()[i].g;
    sum_c += image.pixels()[i].g + residual.pixels()[i].g;
  }
  const double n = static_cast<double>(image.pixels().size());
  return {sum / n, sum_c / n, clamped_fraction(s, rays, view, vpls, clamp, 32, 8)};
}

TEST(BiasCompensation, FurnaceBox) {
  // Every surface emits 1 and reflects 0.5: L = 2 everywhere, half of it reflected.
  const AnalyticScene furnace = furnace_box(1.0, 0.5, 1.0);
  const double expected = *furnace.expected_radiance;
  const Means m = measure(furnace, 0.2f, 512, 32);
  std::printf("furnace, clamp 0.2: clamped %.4f, compensated %.4f, expected %.4f, "
              "clamped_fraction %.4f\n",
              m.clamped, m.compensated, expected, m.fraction);
  // Measured (N = 512, 32x32, 16 gather directions): clamped 1.7721 (-11.4 %), compensated
  // 1.9914 (-0.43 %: the walk's quasi-Monte Carlo error), clamped_fraction 0.2248 against the
  // 0.228 the image lost. Bounds: 1 % (2.3x the measured residual), 0.03.
  EXPECT_LT(m.clamped, 0.95 * expected);
  EXPECT_NEAR(m.compensated, expected, 0.01 * expected);
  EXPECT_NEAR(m.fraction, (expected - m.clamped) / (expected - 1.0), 0.03);
}

TEST(BiasCompensation, IntegratingSphere) {
  const AnalyticScene sphere = integrating_sphere(1.0, 0.7, 2);
  const double expected = *sphere.expected_radiance;
  const Means m = measure(sphere, 0.2f, 512, 32);
  std::printf("sphere, clamp 0.2: clamped %.5f, compensated %.5f, expected %.5f, "
              "clamped_fraction %.4f\n",
              m.clamped, m.compensated, expected, m.fraction);
  // Measured (2 subdivisions, N = 512, 32x32): clamped 0.03241 (-4.9 %: no corners, only the
  // clamp near every VPL), compensated 0.03394 (-0.44 %). Bound 1 %.
  EXPECT_LT(m.clamped, 0.98 * expected);
  EXPECT_NEAR(m.compensated, expected, 0.01 * expected);
}

// The same residual from the clamped image where the camera sees the gather hits: the furnace's
// camera sees about half of the box, so both halves of walk/compensation/screen_compensation.h are
// at work.
TEST(ScreenCompensation, FurnaceBox) {
  const AnalyticScene furnace = furnace_box(1.0, 0.5, 1.0);
  const double expected = *furnace.expected_radiance;
  for (bool local : {false, true}) {
    const Means m = measure_screen(furnace, 0.2f, 512, 32, local);
    std::printf("furnace, %s clamp 0.2: clamped %.4f, on screen %.4f, expected %.4f, "
                "fallback %.3f\n",
                local ? "local" : "global", m.clamped, m.screen, expected, m.screen_fallback);
    // Measured (N = 512, 32x32, 16 gathers, 3 iterations, batched, k = 4): global: clamped
    // 1.7742 (-11.3 %), compensated 1.9976 (-0.12 %), 7.2 % of the samples exact; local:
    // clamped 1.9480 (-2.6 %), compensated 1.9873 (-0.64 %), 0.6 % exact. Bound 1 % (1.6x).
    // (A gather hit looked up only in its own pixel, where that pixel's centre sees its surface:
    // -0.06 % and -0.4 %; at 32x32 most hits within the local clamp lie a pixel from a crease,
    // where the image's own pixel shows the other face.)
    EXPECT_LT(m.clamped, (local ? 0.99 : 0.95) * expected);
    EXPECT_NEAR(m.screen, expected, 0.01 * expected);
    EXPECT_GT(m.screen_fallback, 0.003); // the exact path is exercised
    EXPECT_LT(m.screen_fallback, 0.5);   // and the image path
  }
}

TEST(ScreenCompensation, IntegratingSphere) {
  const AnalyticScene sphere = integrating_sphere(1.0, 0.7, 2);
  const double expected = *sphere.expected_radiance;
  const Means m = measure_screen(sphere, 0.2f, 512, 32, false);
  std::printf("sphere, clamp 0.2: clamped %.5f, on screen %.5f, expected %.5f\n", m.clamped,
              m.screen, expected);
  // Measured: clamped 0.03241 (-4.9 %), compensated on screen 0.03397 (-0.35 %, as the
  // ray-traced compensation above: -0.44 %). Bound 1 %.
  EXPECT_LT(m.clamped, 0.98 * expected);
  EXPECT_NEAR(m.screen, expected, 0.01 * expected);
}

} // namespace IRAD_UNITY_ID
} // namespace irad
