// The raster against answers no estimator of ours defines (design.md section 3).
#include "core/camera/view.h"
#include "core/image/image_metrics.h"
#include "core/mesh/sphere_mesh.h"
#include "core/scene/scene_builder.h"
#include "raster/raster_renderer.h"
#include "tests/square_light_error.h"
#include "tests/test_rooms.h"
#include "walk/vpls/quasi_random_walk.h"

#include <cstdio>
#include <gtest/gtest.h>

namespace irad {
namespace IRAD_UNITY_ID {

// A 1 m square light of radiance 1 at 1 m over a 6 m grey plane (albedo 0.5), seen obliquely.
// Expected pixel: rho E(x) / pi, with E from Lambert's formula; the light's albedo is 0, so only
// direct light reaches the plane. Error sources: N-point quadrature over the light, shadow-map
// bias on the plane itself; the clamp distance (0.05 * 6.2 m = 0.31 m) is below the light's
// height, so the clamp removes nothing.
TEST(RasterAnalytic, SquareLightOverPlaneMatchesLambert) {
  const LambertError e = square_light_error(1, 256);
  // Measured (llvmpipe, N = 1024, 256^2 shadow faces): relative RMS 0.00161, max 0.0029. The
  // bounds leave ~2.5x room for other GL implementations' rounding; a shadow-acne or cosine bug
  // costs far more (a missing 1/pi alone is a factor of 3).
  EXPECT_GT(e.count, 10000);
  EXPECT_LT(e.rel_rms, 0.004);
  EXPECT_LT(e.max_rel, 0.008);
}

// Interleaved sampling: each pixel sees 1/16 of the light's VPLs (a share of the paths dealt out in
// blocks of 16, core/lights/interleave_sets.h),
// and the resolve averages the 16 sets over a 5x5 window centred on it (outer rows and
// columns at half weight) on the same surface: a blur of about two pixels, which this small
// image (a pixel covers up to 8 cm of the plane) makes visible.
TEST(RasterAnalytic, InterleavedSquareLightOverPlaneMatchesLambert) {
  const LambertError e = square_light_error(4, 0);
  // Measured: relative RMS 0.0079, max 0.063 (next to the light's silhouette, where the window
  // keeps only part of the sets; sets by a hash of the path: 0.0076, 0.062); at 320x240 the RMS
  // is about half. With an uncentred window (a plain k x k window is half a pixel off centre) the
  // RMS is 0.041; with sets taken as path mod 16 (Halton strips) the max is 0.15. Bounds: 1.5x
  // the measurement.
  EXPECT_GT(e.count, 10000);
  EXPECT_LT(e.rel_rms, 0.012);
  EXPECT_LT(e.max_rel, 0.09);
}

// The interleaved resolve on a smooth curved surface: a sphere about 12 pixels wide (smooth
// normals, about 5 degrees per pixel) under a square light, the VPLs of 256 paths. Interleaved,
// each pixel is lit by one of the k^2 sets, so where the resolve keeps only a pixel's own set the
// image shows the sets' differences as a k x k pattern; averaged over the window it approaches
// the image of every VPL at every pixel (k = 1, the same VPLs: the exact sum the sets split).
TEST(RasterAnalytic, InterleavedResolveAveragesACurvedSurface) {
  Log log([](const std::string&) {});
  Scene s;
  const std::uint32_t grey = add_material(s, glm::vec3(0.6f));
  const std::uint32_t light = add_material(s, glm::vec3(0.0f), glm::vec3(4.0f));
  add_sphere(s, {0.0f, 0.0f, 0.0f}, 0.5f, 48, grey);
  add_quad(s, {-0.6f, 1.5f, -0.6f}, {0.6f, 1.5f, -0.6f}, {0.6f, 1.5f, 0.6f}, {-0.6f, 1.5f, 0.6f},
           light);
  s.cameras.push_back(look_at({0.0f, 0.6f, 3.0f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 1.0f));
  finish(s);
  const RayScene rays(s);
  const View view = make_view(s.cameras.at(0), s.bounds, 64, 64);
  const VplSet vpls = quasi_random_walk(s, rays, {256, 64}, log);
  RasterOptions every;
  every.interleave = 1;
  const Image reference = RasterRenderer(s, every).render(view, vpls);
  for (const int k : {2, 4}) {
    RasterOptions o;
    o.interleave = k;
    const Image image = RasterRenderer(s, o).render(view, vpls);
    const ImageMetrics m = compare_images(image, reference);
    std::printf("sphere under a square light, k = %d against k = 1: relMSE %.3g, mean ratio %.4f\n",
                k, m.relmse, m.mean_ratio[1]);
    // Measured: k = 2 2.83e-5, k = 4 1.41e-4, means 0.9996 and 0.9991; with a pixel's own plane
    // as the window's test (not the normals' bisector) 8.94e-5 and 3.96e-4. Bounds ~1.7x.
    EXPECT_LT(m.relmse, k == 2 ? 5e-5 : 2.4e-4);
    EXPECT_NEAR(m.mean_ratio[1], 1.0, 0.003);
  }
}

} // namespace IRAD_UNITY_ID
} // namespace irad
