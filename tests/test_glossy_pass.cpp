// The glossy camera pass (walk/estimators/glossy_pass.h): where a surface's lobe is narrow the VPLs
// shade its diffuse lobe alone and rays from the camera add its specular lobe. Against the path
// tracer (an estimator that shares neither the VPLs nor the image lookups), over the pixels whose
// lobe is traced, on data/cornell_glossy.gltf (metal block r 0.3, plastic block r 0.2, floor r
// 0.45), unclamped (clamp 0: no estimator here is biased but by the pass's own approximations).
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "tests/test_paths.h"
#include "walk/compensation/screen_lookup.h"
#include "walk/estimators/glossy_pass.h"
#include "walk/estimators/path_tracer.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/vpls/quasi_random_walk.h"

#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>

namespace irad {
namespace IRAD_UNITY_ID {

constexpr float kTraced = 0.35f; // the blocks' lobes, not the floor's

// The mean of `image` over the pixels whose centre sees a narrow lobe, per channel.
glm::dvec3 narrow_mean(const Image& image, const ScreenLookup& screen, const View& view,
                       std::size_t* count = nullptr) {
  glm::dvec3 sum(0.0);
  std::size_t n = 0;
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x)
      if (const PixelCentre& c = screen.centre(x, y); c && narrow_lobe(*c, kTraced)) {
        sum += glm::dvec3(image.at(x, y));
        ++n;
      }
  if (count) *count = n;
  return n > 0 ? sum / double(n) : sum;
}

TEST(GlossyPass, TracedSpecularLobesMatchThePathTracer) {
  Log log([](const std::string&) {});
  const Scene scene =
      load_gltf(std::filesystem::path(IRAD_SOURCE_DIR) / "data" / "cornell_glossy.gltf", log);
  const RayScene rays(scene);
  const View view = make_view(scene.cameras[0], scene.bounds, 48, 48);
  const ScreenLookup screen(scene, rays, view, 0);
  PathTracerOptions pt;
  pt.spp = 512;
  std::size_t pixels = 0;
  const glm::dvec3 truth = narrow_mean(path_trace(scene, rays, view, pt), screen, view, &pixels);
  WalkOptions w;
  w.paths = 1024;
  const VplSet vpls = quasi_random_walk(scene, rays, w, log);
  VplTracerOptions rt{0.0f, 0};
  const glm::dvec3 full = narrow_mean(trace_vpls(scene, rays, view, vpls, rt), screen, view);
  rt.traced_roughness = kTraced;
  Image image = trace_vpls(scene, rays, view, vpls, rt);
  const glm::dvec3 diffuse = narrow_mean(image, screen, view);
  GlossyPassOptions o;
  o.roughness = kTraced;
  o.samples = 64;
  o.clamp = 0.0f;
  GlossyPassStats stats;
  add_glossy_pass(scene, rays, view, vpls, o, image, &stats);
  const glm::dvec3 traced = narrow_mean(image, screen, view);
  std::printf("%zu narrow pixels, %llu rays (%llu read from the image, %llu gathered): pt %.4f "
              "%.4f %.4f; VPLs alone %.4f %.4f %.4f; their diffuse lobe %.4f %.4f %.4f; with the "
              "pass %.4f %.4f %.4f\n",
              pixels, static_cast<unsigned long long>(stats.rays),
              static_cast<unsigned long long>(stats.on_screen),
              static_cast<unsigned long long>(stats.exact), truth.x, truth.y, truth.z, full.x,
              full.y, full.z, diffuse.x, diffuse.y, diffuse.z, traced.x, traced.y, traced.z);
  EXPECT_EQ(stats.pixels, pixels);
  for (int c = 0; c < 3; ++c) {
    // Measured (418 pixels, 1024 paths, 64 rays a pixel): with the pass -2.2 %, -0.4 %, -3.0 %
    // of pt 512 spp (gcc, Release); clang's build (the sanitizers': other float round-off, other
    // paths and hits) has moved such figures by up to 2.4 points. The diffuse lobe alone a third;
    // the VPLs alone, unclamped, +10 % (spikes). The bound: 1.5x the worst of 3.0 + 2.4.
    EXPECT_LT(diffuse[c], 0.5 * truth[c]);
    EXPECT_NEAR(traced[c] / truth[c], 1.0, 0.08) << "channel " << c;
  }
}

// The relative mean squared difference of two images over the narrow-lobe pixels:
// sum (a - b)^2 / sum b^2, channels together.
double narrow_difference(const Image& a, const Image& b, const ScreenLookup& screen,
                         const View& view) {
  double d = 0.0, n = 0.0;
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x)
      if (const PixelCentre& c = screen.centre(x, y); c && narrow_lobe(*c, kTraced))
        for (int k = 0; k < 3; ++k) {
          const double u = a.at(x, y)[k], v = b.at(x, y)[k];
          d += (u - v) * (u - v);
          n += v * v;
        }
  return n > 0.0 ? d / n : 0.0;
}

// Glossy-to-glossy light: the floor turned into metal of roughness 0.1, so that the metal block
// shows the floor, which shows the walls, and the floor the blocks. Where a ray from a narrow lobe
// meets another narrow lobe the pass traces on through it; with bounces = 0 it takes 32 VPLs drawn
// by power there through the narrow lobe, which few of them light: as unbiased, and far noisier
// (unclamped here; with the clamp, as irad renders, those few are clamped too).
TEST(GlossyPass, NarrowLobesSeenInNarrowLobesAreTracedOn) {
  Log log([](const std::string&) {});
  Scene scene =
      load_gltf(std::filesystem::path(IRAD_SOURCE_DIR) / "data" / "cornell_glossy.gltf", log);
  for (Material& m : scene.materials)
    if (m.name == "semi_gloss_floor") {
      m.metallic = 1.0f;
      m.roughness = 0.1f;
    }
  const RayScene rays(scene);
  const View view = make_view(scene.cameras[0], scene.bounds, 48, 48);
  const ScreenLookup screen(scene, rays, view, 0);
  WalkOptions w;
  w.paths = 1024;
  const VplSet vpls = quasi_random_walk(scene, rays, w, log);
  VplTracerOptions rt{0.0f, 0};
  rt.traced_roughness = kTraced;
  const Image diffuse = trace_vpls(scene, rays, view, vpls, rt);
  GlossyPassOptions o;
  o.roughness = kTraced;
  o.samples = 64;
  o.clamp = 0.0f;
  glm::dvec3 mean[2];
  double noise[2];
  for (const int bounces : {0, 3}) {
    Image image[2] = {diffuse, diffuse};
    o.bounces = bounces;
    GlossyPassStats stats;
    for (int seed = 0; seed < 2; ++seed) {
      o.seed = static_cast<std::uint64_t>(seed) + 1;
      add_glossy_pass(scene, rays, view, vpls, o, image[seed], &stats);
    }
    const int b = bounces > 0 ? 1 : 0;
    mean[b] = (narrow_mean(image[0], screen, view) + narrow_mean(image[1], screen, view)) * 0.5;
    noise[b] = narrow_difference(image[0], image[1], screen, view);
    std::printf("bounces %d: %llu rays, %llu gathered; narrow pixels' means %.4f %.4f %.4f, "
                "relMSE between two seeds %.2e\n",
                bounces, static_cast<unsigned long long>(stats.rays),
                static_cast<unsigned long long>(stats.exact), mean[b].x, mean[b].y, mean[b].z,
                noise[b]);
  }
  // Measured (gcc, Release, 641 pixels): relMSE between seeds 9.8e-2 without, 3.5e-3 with the
  // lobes traced on (0.036x); the means -3.8 %, -2.3 %, -2.9 % apart, the noisier run higher.
  // The bounds: 5x the ratio, 2.5x the distance.
  EXPECT_LT(noise[1], 0.2 * noise[0]);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[1][c] / mean[0][c], 1.0, 0.1) << "channel " << c;
}

} // namespace IRAD_UNITY_ID
} // namespace irad
