// Coincident faces, as third-party interiors hold them: a floor stored twice in two
// tessellations, and a zero-thickness wall made of two back-to-back faces. The deferred passes
// (RasterOptions::batch > 1, raster/passes/deferred_shader.h) shade the one surface the G-buffer
// kept per pixel and must agree with rt-vpl (the same VPLs, ray-traced visibility: a ray hits one
// of the coincident faces); the per-VPL forward passes (batch 1, the batched passes' reference)
// add light wherever a fragment passes the depth test and light each coincident face once more.
//
// With IRAD_TEST_IMAGES=DIR the test writes its images to DIR.
#include "core/camera/view.h"
#include "core/image/image_metrics.h"
#include "core/scene/scene_builder.h"
#include "raster/raster_renderer.h"
#include "tests/side_by_side.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/vpls/quasi_random_walk.h"

#include <cstdio>
#include <gtest/gtest.h>
#include <string>

namespace irad {
namespace IRAD_UNITY_ID {

Log quiet_log() {
  return Log([](const std::string&) {});
}

// A floor z = 0 (2 triangles) with a copy of itself as a 3 x 3 grid of quads (18 triangles), and
// a wall y = 1 of two faces, one facing the light and the camera (-y), one facing away (+y),
// with the same corners; a point light in front of the wall.
Scene coincident_scene() {
  Scene s;
  const std::uint32_t floor = add_material(s, glm::vec3(0.5f));
  const std::uint32_t wall = add_material(s, {0.7f, 0.6f, 0.5f});
  add_quad(s, {-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, floor);
  const auto at = [](int k) { return -2.0f + 4.0f * static_cast<float>(k) / 3.0f; };
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const float x0 = at(i), x1 = at(i + 1), y0 = at(j), y1 = at(j + 1);
      add_quad(s, {x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}, floor);
    }
  add_quad(s, {-2, 1, 0}, {-2, 1, 2}, {2, 1, 2}, {2, 1, 0}, wall); // faces -y
  add_quad(s, {-2, 1, 0}, {2, 1, 0}, {2, 1, 2}, {-2, 1, 2}, wall); // faces +y
  PunctualLight point;
  point.name = "point";
  point.position = {-0.5f, -0.6f, 1.4f};
  point.intensity = glm::vec3(4.0f);
  s.lights = {point};
  s.cameras.push_back(look_at({0.0f, -3.5f, 2.2f}, {0.0f, 0.5f, 0.5f}, {0, 0, 1}, 0.9f));
  finish(s);
  return s;
}

TEST(CoincidentFaces, DeferredPassesLightEachSurfaceOnceAsRtVpl) {
  Log log = quiet_log();
  const Scene scene = coincident_scene();
  const RayScene rays(scene);
  const VplSet vpls = quasi_random_walk(scene, rays, {128, 64}, log);
  const View view = make_view(scene.cameras.at(0), scene.bounds, 96, 96);
  const Image traced = trace_vpls(scene, rays, view, vpls, {RasterOptions{}.clamp, 0});
  for (int k : {1, 4}) {
    RasterOptions forward;
    forward.interleave = k;
    forward.batch = 1;
    RasterOptions deferred = forward;
    deferred.batch = 16;
    const Image a = RasterRenderer(scene, forward).render(view, vpls);
    const Image b = RasterRenderer(scene, deferred).render(view, vpls);
    EXPECT_EQ(b.non_finite_count(), 0u);
    const ImageMetrics f = compare_images(a, traced), d = compare_images(b, traced);
    const Image error = relative_error_image(b, traced, {0.05, 1});
    maybe_write_side_by_side("coincident_k" + std::to_string(k), {&a, &b, &traced, &error});
    std::printf("k = %d against rt-vpl: forward relMSE %.3g mean ratio %.4f | deferred relMSE %.3g "
                "mean ratio %.4f\n",
                k, f.relmse, f.mean_ratio[1], d.relmse, d.mean_ratio[1]);
    // Measured (llvmpipe, 96 x 96, N = 128): deferred k = 1 relMSE 8.3e-7, mean ratio 0.9996;
    // k = 4 relMSE 1.0e-3, mean ratio 1.0001 (the resolve's error, at the wall's foot). The
    // forward passes light both copies: relMSE 0.36 / 0.32, mean ratio 1.63 (k = 1), 1.66 (k = 4).
    EXPECT_NEAR(d.mean_ratio[1], 1.0, 0.005);
    EXPECT_LT(d.relmse, k == 1 ? 1e-5 : 4e-3);
    // The scene does hold coincident faces the depth test lets through twice.
    EXPECT_GT(f.mean_ratio[1], 1.5);
  }
}

} // namespace IRAD_UNITY_ID
} // namespace irad
