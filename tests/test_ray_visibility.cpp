// The raster's visibility by rays (RasterOptions::visibility, walk/estimators/visibility_tracer.h):
// over the same VPLs the image is rt-vpl's but where a pixel's G-buffer surface differs from its
// primary ray's hit, far nearer rt-vpl than the shadow maps come; Auto keeps the maps on a scene
// whose shadow faces draw few triangles; the options rays cannot serve are refused.
#include "core/gltf/loader.h"
#include "core/image/image_metrics.h"
#include "core/util/error.h"
#include "irad/render.h"
#include "raster/raster_renderer.h"
#include "tests/test_paths.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>

namespace irad {
namespace IRAD_UNITY_ID {

Log quiet_log() {
  return Log([](const std::string&) {});
}

const std::filesystem::path data = std::filesystem::path(IRAD_SOURCE_DIR) / "data";

// Every VPL of 256 paths on every pixel (no clusters, no interleaving, no compensation).
RenderOptions every_vpl(Estimator estimator, Visibility visibility) {
  RenderOptions o;
  o.size = std::pair{48, 48};
  o.walk.paths = 256;
  o.screen_compensation = false;
  o.estimator = estimator;
  o.raster.interleave = 1;
  o.raster.visibility = visibility;
  return o;
}

// How image a departs from rt-vpl's `exact`, value by value (R, G, B of every pixel):
// |a - e| / (e + 0.01), the mean of the lowest 99 % and the count above 1 %. A pixel whose centre
// lies on a silhouette shows a different surface in the G-buffer than on the primary ray (both
// visibility methods share those few); visibility shows everywhere else.
struct Departure {
  double trimmed_mean = 0.0;
  std::size_t over = 0;
};
Departure departure(const Image& a, const Image& exact) {
  std::vector<float> d;
  for (int y = 0; y < exact.height(); ++y)
    for (int x = 0; x < exact.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        const float e = exact.at(x, y)[c];
        d.push_back(std::abs(a.at(x, y)[c] - e) / (e + 0.01f));
      }
  std::sort(d.begin(), d.end());
  Departure out;
  const std::size_t keep = d.size() * 99 / 100;
  for (std::size_t i = 0; i < keep; ++i) out.trimmed_mean += d[i];
  out.trimmed_mean /= static_cast<double>(keep);
  out.over = static_cast<std::size_t>(
      std::count_if(d.begin(), d.end(), [](float v) { return v > 0.01f; }));
  return out;
}

// Against rt-vpl over the same VPLs (491 of 256 paths, 48x48). Measured (llvmpipe): rays
// trimmed mean 1.3e-5 on all three boxes, 3 values over 1 % (one silhouette pixel, (24, 20));
// maps 2.2e-3 / 452 (Cornell box), 2.2e-3 / 446 (glossy), 3.4e-3 / 718 (mirror wall, its
// mirrored VPLs by their own rays).
TEST(RayVisibility, RtVplsImageOverTheSameVpls) {
  for (const char* file : {"cornell_box.gltf", "cornell_glossy.gltf", "cornell_mirror.gltf"}) {
    Log log = quiet_log();
    const Scene scene = load_gltf(data / file, log);
    const RenderResult exact = render(scene, every_vpl(Estimator::RtVpl, Visibility::Auto), log);
    const RenderResult rays = render(scene, every_vpl(Estimator::Raster, Visibility::Rays), log);
    const RenderResult maps = render(scene, every_vpl(Estimator::Raster, Visibility::Maps), log);
    EXPECT_EQ(rays.visibility, "rays") << file;
    EXPECT_EQ(maps.visibility, "maps") << file;
    const Departure by_rays = departure(rays.image, exact.image);
    const Departure by_maps = departure(maps.image, exact.image);
    EXPECT_LT(by_rays.trimmed_mean, 1e-4) << file;
    EXPECT_LE(by_rays.over, 6u) << file; // two silhouette pixels
    EXPECT_GT(by_maps.over, 20 * by_rays.over) << file;
    EXPECT_GT(rays.seconds.visibility, 0.0) << file;
  }
}

// Auto on a CPU renderer keeps the maps where a batch draws few triangles per VPL against the
// pixels each VPL shades (BatchedPasses::kPixelsPerTriangle): the Cornell box's 160 (its
// faces') against 4096 at 128x128, k = 2.
TEST(RayVisibility, AutoKeepsMapsOnALightScene) {
  Log log = quiet_log();
  const Scene scene = load_gltf(data / "cornell_box.gltf", log);
  RenderOptions o = every_vpl(Estimator::Raster, Visibility::Auto);
  o.size = std::pair{128, 128};
  o.raster.interleave = 2;
  const RenderResult r = render(scene, o, log);
  EXPECT_EQ(r.visibility, "maps");
}

TEST(RayVisibility, RefusesWhatItCannotServe) {
  RasterOptions o;
  o.visibility = Visibility::Rays;
  EXPECT_NO_THROW(check_raster_options(o));
  o.jitter = true;
  EXPECT_THROW(check_raster_options(o), Error);
  o.jitter = false;
  o.batch = 1;
  EXPECT_THROW(check_raster_options(o), Error);
  o.batch = 64;
  o.edge_pixels = EdgePixelMode::Shaded;
  EXPECT_THROW(check_raster_options(o), Error);
  o.visibility = Visibility::Auto; // Auto takes maps there
  EXPECT_NO_THROW(check_raster_options(o));
  EXPECT_NE(rays_refused(o), nullptr);
}

} // namespace IRAD_UNITY_ID
} // namespace irad
