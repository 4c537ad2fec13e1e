// The glossy camera pass (walk/glossy_pass.h): where a surface's lobe is narrow the VPLs shade its
// diffuse lobe alone and rays from the camera add its specular lobe. Against the path tracer
// (an estimator that shares neither the VPLs nor the image lookups), over the pixels whose lobe
// is traced, on data/cornell_glossy.gltf (metal block r 0.3, plastic block r 0.2, floor r 0.45),
// unclamped (clamp 0: no estimator here is biased but by the pass's own approximations).
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "tests/test_paths.h"
#include "walk/glossy_pass.h"
#include "walk/path_tracer.h"
#include "walk/quasi_random_walk.h"
#include "walk/screen_lookup.h"
#include "walk/vpl_tracer.h"

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
              pixels, (unsigned long long)stats.rays, (unsigned long long)stats.on_screen,
              (unsigned long long)stats.exact, truth.x, truth.y, truth.z, full.x, full.y, full.z,
              diffuse.x, diffuse.y, diffuse.z, traced.x, traced.y, traced.z);
  EXPECT_EQ(stats.pixels, pixels);
  for (int c = 0; c < 3; ++c) {
    // Measured (418 pixels, 1024 paths, 64 rays a pixel): with the pass -1.7 %, +0.8 %, -1.5 %
    // of pt 512 spp (gcc, Release), -2.8 %, -0.4 %, -3.9 % (clang, the sanitizers' build: other
    // float round-off, other paths and hits); the diffuse lobe alone a third; the VPLs alone,
    // unclamped, +10 % (spikes). The bound: 1.5x the worst.
    EXPECT_LT(diffuse[c], 0.5 * truth[c]);
    EXPECT_NEAR(traced[c] / truth[c], 1.0, 0.06) << "channel " << c;
  }
}

} // namespace IRAD_UNITY_ID
} // namespace irad
