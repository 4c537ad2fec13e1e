// Batched VPL passes (RasterOptions::batch > 1, raster/passes/batched_passes.h) against the per-VPL
// passes (batch = 1, the reference) with the same VPLs, and against Lambert's formula.
// With IRAD_TEST_IMAGES=DIR the tests write their images to DIR.
#include "core/camera/view.h"
#include "core/environment/environment.h"
#include "core/gltf/loader.h"
#include "core/image/image_metrics.h"
#include "core/scene/scene_builder.h"
#include "raster/raster_renderer.h"
#include "tests/side_by_side.h"
#include "tests/square_light_error.h"
#include "tests/test_paths.h"
#include "walk/vpls/quasi_random_walk.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <string>

namespace irad {
namespace IRAD_UNITY_ID {

Log quiet_log() {
  return Log([](const std::string&) {});
}

struct Difference {
  ImageMetrics metrics;
  double differing = 0.0; // share of pixels whose value differs by more than 1 % (relative)
};

// Renders `vpls` with batch 1 and with `batch`, interleave k, and compares the two.
Difference batched_against_reference(const Scene& scene, const VplSet& vpls, const View& view,
                                     int k, int batch, const std::string& name) {
  RasterOptions reference;
  reference.interleave = k;
  reference.batch = 1;
  RasterOptions batched = reference;
  batched.batch = batch;
  RasterTimings ta, tb;
  const Image a = RasterRenderer(scene, reference).render(view, vpls, &ta);
  const Image b = RasterRenderer(scene, batched).render(view, vpls, &tb);
  // One VPL pipeline: the reference draws every VPL alone, the batched passes none.
  EXPECT_EQ(ta.single_passes, ta.passes);
  EXPECT_EQ(tb.single_passes, 0u);
  EXPECT_EQ(tb.passes, ta.passes);
  EXPECT_EQ(a.non_finite_count(), 0u);
  EXPECT_EQ(b.non_finite_count(), 0u);
  Difference d{compare_images(b, a), 0.0};
  std::size_t differing = 0;
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const glm::vec4 p = a.at(x, y), q = b.at(x, y);
      const float m = std::max({std::abs(p.r), std::abs(p.g), std::abs(p.b), 1e-3f});
      if (std::abs(p.r - q.r) > 0.01f * m || std::abs(p.g - q.g) > 0.01f * m ||
          std::abs(p.b - q.b) > 0.01f * m)
        ++differing;
    }
  d.differing = static_cast<double>(differing) / (view.width * view.height);
  const Image error = relative_error_image(b, a, {0.02, 1});
  maybe_write_side_by_side("batched_" + name, {&a, &b, &error});
  std::printf("%s, k = %d, batch %d against batch 1: relMSE %.3g, max abs %.3g, mean ratio %.6f,"
              " pixels off by > 1 %%: %.4f %%\n",
              name.c_str(), k, batch, d.metrics.relmse, d.metrics.max_abs_error,
              d.metrics.mean_ratio[1], 100.0 * d.differing);
  return d;
}

const std::filesystem::path cornell =
    std::filesystem::path(IRAD_SOURCE_DIR) / "data/cornell_box.gltf";

// What may separate the two paths: texels at the edge of a cube face where the hand-made face
// selection and GL's cube-map sampler could disagree (rounding), the order in which the VPLs are
// summed, and, interleaved, pixels whose centre lies on an edge between two faces: the per-VPL
// passes rasterize each set's tile through its own shifted projection, the deferred passes read
// the surface the full-resolution G-buffer kept (the one the resolve also uses), and rounding
// may pick the other face. A wrong face, texel or block costs far more: with the +x face read
// mirrored relMSE is 1.9e-3 and 39 % of the pixels are off by more than 1 %.
TEST(Batched, CornellBoxMatchesThePerVplPasses) {
  Log log = quiet_log();
  const Scene scene = load_gltf(cornell, log);
  const RayScene rays(scene);
  const VplSet vpls = quasi_random_walk(scene, rays, {128, 64}, log);
  const View view = make_view(scene.cameras.at(0), scene.bounds, 128, 128);
  for (int k : {1, 4}) {
    // Batches of 7 leave a partial last batch and put VPLs of every set into one draw.
    for (int batch : {7, 32}) {
      const Difference d = batched_against_reference(scene, vpls, view, k, batch, "cornell");
      // Measured (llvmpipe, deferred): k = 1: relMSE 1.4e-8 (max abs 2.2e-3), 2 pixels (0.012 %)
      // off by 1 %; k = 4: relMSE 4.6e-6, mean ratio 1.000055, 16 pixels (0.098 %) off by more
      // than 1 %, on the edges of the blocks (the faces the G-buffer and the tile disagree on).
      // Without the occluder planes (raster/glsl/cube_glsl.h) k = 1 gives 1.1e-14 and no pixel:
      // the planes' gradients are dFdx/dFdy over 2x2 quads that lie differently in a cube face
      // and in the atlas, and the neighbour test that drops a plane is a threshold on them.
      EXPECT_LT(d.metrics.relmse, k == 1 ? 2e-7 : 2e-5);
      EXPECT_NEAR(d.metrics.mean_ratio[1], 1.0, 1e-4);
      EXPECT_LT(d.differing, k == 1 ? 0.001 : 0.003);
    }
  }
}

// Mirrored VPLs (data/cornell_mirror.gltf) in the batched passes: their unfolded cubes in the
// atlas (the real and the reflected scene), the pyramid test in the deferred shader; the mirror
// receives no diffuse light either way.
TEST(Batched, MirrorBoxMatchesThePerVplPasses) {
  Log log = quiet_log();
  const Scene scene =
      load_gltf(std::filesystem::path(IRAD_SOURCE_DIR) / "data/cornell_mirror.gltf", log);
  const RayScene rays(scene);
  const VplSet vpls = quasi_random_walk(scene, rays, {64, 64}, log);
  ASSERT_TRUE(
      std::any_of(vpls.vpls.begin(), vpls.vpls.end(), [](const Vpl& v) { return v.mirror >= 0; }));
  const View view = make_view(scene.cameras.at(0), scene.bounds, 96, 96);
  for (int k : {1, 4}) {
    const Difference d = batched_against_reference(scene, vpls, view, k, 16, "mirror");
    // Measured: relMSE 2.7e-8, max abs 1.5e-3 (k = 1; 0.065 % of the pixels off by more than
    // 1 %) and 1e-13 (k = 4) (the atlas's gradients, as for the Cornell box: 1.4e-14 without
    // the occluder planes; without the concave corners of cube_glsl.h, another threshold on
    // them, 4.1e-9 and no pixel). With the mirror's albedo not zeroed in the batched
    // pass: relMSE 0.63 at k = 1. Without the pyramid test in the deferred shader, or without the
    // reflected scene in the atlas's cubes: relMSE 3.0e-3 (k = 1), 39 % of the pixels off by more
    // than 1 %.
    EXPECT_LT(d.metrics.relmse, 1e-7);
    EXPECT_NEAR(d.metrics.mean_ratio[1], 1.0, 1e-4);
    EXPECT_LT(d.differing, 0.001);
  }
}

// Point and spot lights light all six cube faces (no hemisphere): floor, wall and a floating
// occluder (as tests/test_punctual_lights.cpp) lit by both at once.
Scene point_and_spot_scene() {
  Scene s;
  const std::uint32_t floor = add_material(s, glm::vec3(0.5f));
  const std::uint32_t wall = add_material(s, {0.7f, 0.6f, 0.5f});
  const std::uint32_t occluder = add_material(s, glm::vec3(0.6f));
  add_quad(s, {-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, floor);
  add_quad(s, {-2, 1.5f, 0}, {2, 1.5f, 0}, {2, 1.5f, 2}, {-2, 1.5f, 2}, wall);
  add_quad(s, {-0.4f, -0.4f, 0.7f}, {0.4f, -0.4f, 0.7f}, {0.4f, 0.4f, 0.7f}, {-0.4f, 0.4f, 0.7f},
           occluder);
  PunctualLight point;
  point.name = "point";
  point.position = {-0.6f, -0.4f, 1.8f};
  point.intensity = glm::vec3(4.0f);
  PunctualLight spot;
  spot.name = "spot";
  spot.kind = PunctualLight::Kind::Spot;
  spot.position = {0.5f, -0.8f, 2.0f};
  spot.direction = glm::normalize(glm::vec3(0.0f, 0.3f, 0.0f) - spot.position);
  spot.intensity = glm::vec3(8.0f);
  spot.inner_cone = 0.35f;
  spot.outer_cone = 0.6f;
  s.lights = {point, spot};
  s.cameras.push_back(look_at({0.0f, -3.5f, 2.6f}, {0.0f, 0.3f, 0.4f}, {0, 0, 1}, 0.9f));
  finish(s);
  return s;
}

TEST(Batched, PointAndSpotLightsMatchThePerVplPasses) {
  Log log = quiet_log();
  const Scene scene = point_and_spot_scene();
  const RayScene rays(scene);
  const VplSet vpls = quasi_random_walk(scene, rays, {128, 64}, log);
  const auto punctual = std::count_if(vpls.vpls.begin(), vpls.vpls.end(), [](const Vpl& v) {
    return v.kind == VplKind::Point || v.kind == VplKind::Spot;
  });
  ASSERT_GT(punctual, 100); // both kinds of six-face cubes take part
  const View view = make_view(scene.cameras.at(0), scene.bounds, 128, 128);
  for (int k : {1, 4}) {
    const Difference d = batched_against_reference(scene, vpls, view, k, 32, "punctual");
    // Measured (llvmpipe): relMSE 0, the same bits, at k = 1 and 4. With the +x face mirrored:
    // relMSE 3.6e-7 and 0.25 % of the pixels off by more than 1 %.
    EXPECT_LT(d.metrics.relmse, 1e-8);
    EXPECT_NEAR(d.metrics.mean_ratio[1], 1.0, 1e-4);
    EXPECT_LT(d.differing, 0.001);
  }
}

// Directional VPLs in the batched passes (their orthographic maps in an atlas,
// raster/shadow/ortho_atlas.h): a directional light, whose VPLs share one map per batch, and a
// sky, each of whose VPLs has a direction (and a map) of its own, with the point and spot
// lights' cubes in the same batches.
Scene sun_and_sky_scene() {
  Scene scene = point_and_spot_scene();
  PunctualLight sun;
  sun.name = "sun";
  sun.kind = PunctualLight::Kind::Directional;
  sun.direction = glm::normalize(glm::vec3(0.3f, 0.5f, -1.0f));
  sun.intensity = glm::vec3(1.5f);
  scene.lights.push_back(sun);
  scene.environment =
      std::make_shared<Environment>(Environment::uniform(glm::vec3(0.4f, 0.5f, 0.7f), "test"));
  finish(scene);
  return scene;
}

TEST(Batched, DirectionalAndEnvironmentVplsMatchThePerVplPasses) {
  Log log = quiet_log();
  const Scene scene = sun_and_sky_scene();
  const RayScene rays(scene);
  const VplSet vpls = quasi_random_walk(scene, rays, {128, 64}, log);
  const auto directional = std::count_if(vpls.vpls.begin(), vpls.vpls.end(), [](const Vpl& v) {
    return v.kind == VplKind::Directional;
  });
  ASSERT_GT(directional, 40); // the sun's and the sky's
  // 128 x 128 as PointAndSpotLightsMatchThePerVplPasses: at 96 x 96 a pixel row's centres lie
  // within rounding of the wall's foot, and k = 4 flips the whole row between wall and floor
  // (the tile's raster against the G-buffer's: relMSE 1.5e-4, 2 % of the pixels).
  const View view = make_view(scene.cameras.at(0), scene.bounds, 128, 128);
  for (int k : {1, 4}) {
    const Difference d = batched_against_reference(scene, vpls, view, k, 16, "directional");
    // Measured (llvmpipe): relMSE 3.8e-14 (k = 1) and 3.7e-14 (k = 4), max abs 2e-6: the depth
    // read as a window depth rather than the distance itself moves no shadow edge here.
    EXPECT_LT(d.metrics.relmse, 1e-8);
    EXPECT_NEAR(d.metrics.mean_ratio[1], 1.0, 1e-4);
    EXPECT_LT(d.differing, 0.001);
  }
}

// Shadow maps kept per path (RasterRenderer::cache_path, raster/shadow/shadow_cache.h): every
// path's cubes drawn once into atlas pages and shaded from them equal drawing them anew, for
// six-face cubes (two blocks each), mirrored VPLs' unfolded cubes and directional VPLs (their
// orthographic maps drawn per image) too, with the reference (batch 1, one cube per VPL) and the
// batched passes; a page grows while the slots fill it.
TEST(Batched, KeptShadowMapsOfEveryPathMatchDrawingThemAnew) {
  Log log = quiet_log();
  const Scene mirror =
      load_gltf(std::filesystem::path(IRAD_SOURCE_DIR) / "data/cornell_mirror.gltf", log);
  const Scene punctual = point_and_spot_scene(), sky = sun_and_sky_scene();
  for (const Scene* scene : {&punctual, &mirror, &sky}) {
    const RayScene rays(*scene);
    const VplSet vpls = quasi_random_walk(*scene, rays, {96, 64}, log);
    const View view = make_view(scene->cameras.at(0), scene->bounds, 96, 96);
    std::vector<std::vector<Vpl>> paths(96);
    for (const Vpl& v : vpls.vpls) paths.at(v.path).push_back(v);
    for (int batch : {1, 16}) {
      for (int k : {1, 4}) {
        RasterOptions o;
        o.batch = batch;
        o.interleave = k;
        RasterRenderer renderer(*scene, o);
        const Image fresh = renderer.render(view, vpls);
        for (std::uint32_t p = 0; p < paths.size(); ++p) renderer.cache_path(p, paths[p], 96, 96);
        RasterTimings timings;
        const ImageMetrics m = compare_images(renderer.render_cached(view, &timings), fresh);
        std::printf("kept shadow maps, %s, batch %d, k = %d: relMSE %.3g, max abs %.3g, %.2f MB\n",
                    scene == &mirror ? "mirror"
                    : scene == &sky  ? "sun and sky"
                                     : "punctual",
                    batch, k, m.relmse, m.max_abs_error,
                    static_cast<double>(renderer.cache_bytes()) / 1048576.0);
        // Measured: batch 1 identical; batch 16 relMSE up to 3e-14 and max abs 1.1e-6 (the
        // summation order), except the mirror box at k = 1: 9.5e-12 and 5.3e-5 (a lookup whose
        // neighbour texel, which the occluder's plane uses both ways, lies across a block's
        // edge: another block's texel in a page than in the atlas).
        EXPECT_LT(m.max_abs_error, 2e-4);
        EXPECT_LT(m.relmse, 1e-10);
        EXPECT_EQ(timings.single_passes, batch == 1 ? timings.passes : 0u);
      }
    }
  }
}

// `irad render --stats` counts the VPLs drawn one at a time: none with the batched passes, with
// a mirror and jitter; every one with --batch 1.
TEST(Batched, StatsCountTheVplsDrawnOneAtATime) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / "irad_batched_stats";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string base = std::string(IRAD_BINARY) + " render " + IRAD_SOURCE_DIR +
                           "/data/cornell_mirror.gltf --size 32x32 --paths 16 --jitter on "
                           "--quiet -o " +
                           (dir / "m.exr").string() + " --stats " + (dir / "s.json").string();
  for (const char* batch : {"16", "1"}) {
    ASSERT_EQ(std::system((base + " --batch " + batch).c_str()), 0);
    std::ifstream in(dir / "s.json");
    const nlohmann::json stats = nlohmann::json::parse(in);
    const auto passes = stats["passes"].get<std::size_t>();
    EXPECT_GT(passes, 16u);
    EXPECT_EQ(stats["single_passes"].get<std::size_t>(), std::string(batch) == "1" ? passes : 0u)
        << batch;
  }
}

// The analytic answer with the per-VPL passes and with small batches
// (tests/test_raster_analytic.cpp runs the default batch, 16); the bounds are those of that file.
TEST(Batched, SquareLightOverPlaneMatchesLambert) {
  for (int batch : {1, 7}) {
    const LambertError e = square_light_error(1, 256, batch);
    // Measured: relative RMS 0.00161, max 0.0029 with either batch.
    EXPECT_GT(e.count, 10000);
    EXPECT_LT(e.rel_rms, 0.004);
    EXPECT_LT(e.max_rel, 0.008);
    const LambertError i = square_light_error(4, 0, batch);
    // Measured: relative RMS 0.0076, max 0.062 with either batch.
    EXPECT_GT(i.count, 10000);
    EXPECT_LT(i.rel_rms, 0.012);
    EXPECT_LT(i.max_rel, 0.09);
  }
}

} // namespace IRAD_UNITY_ID
} // namespace irad
