// Jittered low-discrepancy sampling (raster/image/pixel_jitter.h, seed section 5.1.1): the offsets,
// and the raster's error along geometric edges against a 16x supersampled reference, with and
// without the jitter, in the reference mode (k = 1) and with interleaved sampling (k = 4).
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/image/image_metrics.h"
#include "raster/image/pixel_jitter.h"
#include "raster/raster_renderer.h"
#include "tests/doc_images.h"
#include "tests/jitter_edges.h"
#include "tests/test_paths.h"
#include "walk/estimators/path_tracer.h"
#include "walk/rays/ray_scene.h"
#include "walk/vpls/quasi_random_walk.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <vector>

namespace irad {
namespace IRAD_UNITY_ID {

namespace fs = std::filesystem;
const fs::path cornell = fs::path(IRAD_SOURCE_DIR) / "data/cornell_box.gltf";

// The image point (pixels, y down) where world point p projects.
glm::vec2 project(const glm::mat4& vp, const glm::vec3& p, int w, int h) {
  const glm::vec4 c = vp * glm::vec4(p, 1.0f);
  const glm::vec2 ndc = glm::vec2(c) / c.w;
  return {(ndc.x * 0.5f + 0.5f) * static_cast<float>(w),
          (0.5f - ndc.y * 0.5f) * static_cast<float>(h)};
}

TEST(PixelJitter, ProjectionMovesTheSamplePointByTheOffset) {
  Log log([](const std::string&) {});
  const Scene scene = load_gltf(cornell, log);
  const View view = make_view(scene.cameras.at(0), scene.bounds, 64, 48);
  const glm::vec3 p(0.3f, 0.2f, 0.1f);
  const glm::vec2 offset(0.3f, -0.2f);
  const glm::vec2 a = project(view.projection * view.view, p, 64, 48);
  const glm::vec2 b =
      project(jittered_projection(view.projection, offset, 64, 48) * view.view, p, 64, 48);
  // Sampling at centre + offset is seeing the image moved by -offset.
  EXPECT_NEAR(b.x - a.x, -offset.x, 1e-4f);
  EXPECT_NEAR(b.y - a.y, -offset.y, 1e-4f);
}

// Every prefix of the particles' points covers the pixel evenly: the n_j particles that reach
// reflection j are a prefix, so each depth is stratified on its own.
TEST(PixelJitter, EveryPrefixIsStratified) {
  for (std::uint32_t n : {16u, 37u, 64u, 100u, 256u, 1000u}) {
    std::vector<int> cells(16, 0);
    for (std::uint32_t i = 0; i < n; ++i) {
      const glm::vec2 u = path_jitter_point(i);
      ASSERT_GE(u.x, 0.0f);
      ASSERT_LT(u.x, 1.0f);
      ASSERT_GE(u.y, 0.0f);
      ASSERT_LT(u.y, 1.0f);
      ++cells[static_cast<int>(u.x * 4) + 4 * static_cast<int>(u.y * 4)];
    }
    const double expected = n / 16.0;
    for (int c : cells) EXPECT_LE(std::abs(c - expected), 2.0 + 0.1 * expected) << n;
  }
}

TEST(PixelJitter, OffsetsStayInsideThePixel) {
  for (std::uint32_t i = 0; i < 500; ++i)
    for (std::uint16_t d : {std::uint16_t(0), std::uint16_t(1), std::uint16_t(5)}) {
      Vpl v;
      v.path = i;
      v.depth = d;
      const glm::vec2 o = vpl_jitter(v);
      EXPECT_LE(std::abs(o.x), 0.5f);
      EXPECT_LE(std::abs(o.y), 0.5f);
    }
  for (int s = 0; s < 16; ++s) {
    const glm::vec2 o = camera_jitter(s, 16);
    EXPECT_LT(std::abs(o.x), 0.5f);
    EXPECT_LE(std::abs(o.y), 0.5f);
  }
}

TEST(PixelJitter, CommandLineOption) {
  const fs::path dir = fs::path(::testing::TempDir()) / "irad_jitter_cli";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string base = std::string(IRAD_BINARY) + " render " + cornell.string() +
                           " --size 32x32 --paths 8 --quiet -o " + (dir / "c.exr").string();
  ASSERT_EQ(std::system((base + " --jitter on --stats " + (dir / "s.json").string()).c_str()), 0);
  std::ifstream in(dir / "s.json");
  EXPECT_TRUE(nlohmann::json::parse(in)["jitter"].get<bool>());
  EXPECT_NE(std::system((base + " --jitter maybe 2>/dev/null").c_str()), 0);
}

// The Cornell box at 64 x 64 (its blocks' silhouettes and the walls' corners make the edges), 64
// paths. The reference is the same raster with the same VPLs at 4x the width and height, box
// downsampled: 16 stratified samples per pixel, so the jittered image and the reference differ
// only by how each samples the pixel footprint (the shadow maps are the same size in both).
struct EdgeErrors {
  jitter_test::MaskedError edge, interior;
};

class JitterEdges : public ::testing::Test {
protected:
  static constexpr int kSize = 64;
  static void SetUpTestSuite() {
    Log log([](const std::string&) {});
    scene_ = new Scene(load_gltf(cornell, log));
    const RayScene rays(*scene_);
    vpls_ = new VplSet(quasi_random_walk(*scene_, rays, {64, 64}, log));
    const View view = make_view(scene_->cameras.at(0), scene_->bounds, kSize, kSize);
    mask_ = new std::vector<std::uint8_t>(jitter_test::edge_mask(*scene_, rays, view, 1));
    reference_ = new Image(jitter_test::box_downsample(render(1, false, 4 * kSize), 4));
  }
  static void TearDownTestSuite() {
    delete scene_;
    delete vpls_;
    delete mask_;
    delete reference_;
  }
  // batch 16: the batched passes (a G-buffer per jitter cell, raster/image/pixel_jitter.h);
  // batch 1: the per-VPL passes, each VPL at its own offset.
  static Image render(int interleave, bool jitter, int size, int batch = 16) {
    RasterOptions options;
    options.interleave = interleave;
    options.jitter = jitter;
    options.shadow_resolution = 256;
    options.batch = batch;
    RasterRenderer raster(*scene_, options);
    RasterTimings timings;
    Image image = raster.render(make_view(scene_->cameras.at(0), scene_->bounds, size, size),
                                *vpls_, &timings);
    EXPECT_EQ(timings.single_passes, batch == 1 ? timings.passes : 0u);
    return image;
  }
  static EdgeErrors errors(const Image& image) {
    return {jitter_test::masked_error(image, *reference_, *mask_, 1),
            jitter_test::masked_error(image, *reference_, *mask_, 0)};
  }
  static void print(const char* name, const EdgeErrors& e) {
    std::printf("%-10s edge (%zu px) rmse %.5f relmse %.5f | interior (%zu px) rmse %.5f relmse "
                "%.5f\n",
                name, e.edge.pixels, e.edge.rmse, e.edge.relmse, e.interior.pixels, e.interior.rmse,
                e.interior.relmse);
  }
  static inline Scene* scene_ = nullptr;
  static inline VplSet* vpls_ = nullptr;
  static inline std::vector<std::uint8_t>* mask_ = nullptr;
  static inline Image* reference_ = nullptr;

  // Documentation pictures (only with IRAD_DOC_IMAGES): off | on | reference, 4x nearest, and
  // their relative errors against the reference.
  static void pictures(const char* name, const Image& off, const Image& on) {
    if (doc_images::directory().empty()) return;
    const Image r = *reference_;
    const auto big = [](const Image& i) {
      return doc_images::magnified_crop(i, 0, 0, kSize, kSize, 4);
    };
    const Image a = big(off), b = big(on), c = big(r);
    doc_images::write(std::string("ext_jitter_") + name + ".png",
                      doc_images::side_by_side({&a, &b, &c}, 8));
    DiffOptions d;
    d.max_error = 0.5;
    const Image ea = big(relative_error_image(off, r, d)), eb = big(relative_error_image(on, r, d));
    doc_images::write(std::string("ext_jitter_") + name + "_error.png",
                      doc_images::side_by_side({&ea, &eb}, 8));
    const Image m = big(doc_images::mask_overlay(r, *mask_));
    doc_images::write("ext_jitter_edge_mask.png", m);
  }
};

TEST_F(JitterEdges, ReferenceModeK1) {
  const Image off_image = render(1, false, kSize), on_image = render(1, true, kSize);
  const EdgeErrors off = errors(off_image);
  const EdgeErrors on = errors(on_image);
  print("k=1 off", off);
  print("k=1 on", on);
  pictures("k1", off_image, on_image);
  // Measured (the batched passes, a G-buffer per jitter cell): edge relMSE 0.0235 -> 0.0046
  // (x0.20), RMSE 0.366 -> 0.076 (x0.21, the light's silhouette: L_e is jittered too).
  EXPECT_LT(on.edge.relmse, 0.4 * off.edge.relmse);
  EXPECT_LT(on.edge.rmse, 0.4 * off.edge.rmse);
  // Interior: RMSE 0.00076 -> 0.00095 (x1.25; with jitter each VPL's hard shadow edge is sampled
  // at one sub-pixel position), relMSE 3e-5 -> 3e-5, both far below the VPLs' own error against pt.
  EXPECT_LT(on.interior.rmse, 2.0 * off.interior.rmse);
  EXPECT_LT(on.interior.relmse, 1e-4);
}

TEST_F(JitterEdges, InterleavedK4) {
  const Image off_image = render(4, false, kSize), on_image = render(4, true, kSize);
  const EdgeErrors off = errors(off_image);
  const EdgeErrors on = errors(on_image);
  print("k=4 off", off);
  print("k=4 on", on);
  pictures("k4", off_image, on_image);
  // Measured: edge RMSE 0.369 -> 0.088 (x0.24), relMSE 0.067 -> 0.048 (x0.71: the resolve takes
  // each pixel's irradiance from its neighbours on the surface its centre sees, so at a depth
  // discontinuity only the albedo and the light's silhouette are filtered fully).
  EXPECT_LT(on.edge.rmse, 0.4 * off.edge.rmse);
  EXPECT_LT(on.edge.relmse, 0.85 * off.edge.relmse);
  // The geometry-aware resolve still works with jittered tiles: interior RMSE 0.01003 -> 0.01008,
  // relMSE 0.00222 -> 0.00228 (interleaving noise dominates both).
  EXPECT_LT(on.interior.rmse, 1.1 * off.interior.rmse);
  EXPECT_LT(on.interior.relmse, 1.1 * off.interior.relmse);
}

// The batched passes' jitter (each VPL at the centre of its offset's cell of a 4 x 4 grid,
// reflection 2 and deeper at the pixel centre) against the per-VPL passes' (each VPL at its own
// offset): the same filtering, as good on edges and in the interior.
TEST_F(JitterEdges, CellsOfTheBatchedPassesFilterAsWellAsPerVplOffsets) {
  for (int k : {1, 4}) {
    const EdgeErrors cells = errors(render(k, true, kSize));
    const EdgeErrors own = errors(render(k, true, kSize, 1));
    print(k == 1 ? "k=1 cells" : "k=4 cells", cells);
    print(k == 1 ? "k=1 own" : "k=4 own", own);
    // Measured: k = 1 edge RMSE 0.0759 (cells) vs 0.0758 (own offsets), relMSE 0.0046 vs
    // 0.0050, interior RMSE 0.00095 vs 0.00107; k = 4 edge RMSE 0.0878 vs 0.0876, relMSE 0.0477
    // vs 0.0469, interior 0.01008 vs 0.01008. Rounding every depth to the 16 cells (the middle
    // ones at +-1/8 for all reflections): k = 1 interior RMSE 0.00181 (x1.7 own).
    EXPECT_LT(cells.edge.rmse, 1.05 * own.edge.rmse) << k;
    EXPECT_LT(cells.edge.relmse, 1.1 * own.edge.relmse) << k;
    EXPECT_LT(cells.interior.rmse, 1.05 * own.interior.rmse) << k;
    EXPECT_LT(cells.interior.relmse, 1.1 * own.interior.relmse) << k;
  }
}

// Shadow maps kept per path (the cached walkthrough) with jitter: the same cells, the same image.
TEST_F(JitterEdges, KeptShadowMapsJitterAsTheFreshRender) {
  const View view = make_view(scene_->cameras.at(0), scene_->bounds, kSize, kSize);
  std::vector<std::vector<Vpl>> paths(64);
  for (const Vpl& v : vpls_->vpls) paths.at(v.path).push_back(v);
  for (int k : {1, 4}) {
    RasterOptions options;
    options.interleave = k;
    options.jitter = true;
    RasterRenderer raster(*scene_, options);
    const Image fresh = raster.render(view, *vpls_);
    for (std::uint32_t p = 0; p < paths.size(); ++p) raster.cache_path(p, paths[p], kSize, kSize);
    RasterTimings timings;
    const ImageMetrics m = compare_images(raster.render_cached(view, &timings), fresh);
    std::printf("k=%d kept shadow maps with jitter: relMSE %.3g, max abs %.3g\n", k, m.relmse,
                m.max_abs_error);
    // Measured: relMSE 0, max abs 0 (the same draws in the same order).
    EXPECT_LT(m.max_abs_error, 1e-5) << k;
    EXPECT_EQ(timings.single_passes, 0u);
  }
}

} // namespace IRAD_UNITY_ID
} // namespace irad

namespace irad {
namespace IRAD_UNITY_ID {

// The same edges against the path tracer sampling each pixel's footprint (box filter, 1024 spp):
// the ground truth the jittered raster converges to, independent of the raster.
TEST_F(JitterEdges, AgainstThePathTracerOverThePixelFootprint) {
  const RayScene rays(*scene_);
  PathTracerOptions o;
  o.spp = 1024;
  o.pixel_footprint = true;
  const Image pt =
      path_trace(*scene_, rays, make_view(scene_->cameras.at(0), scene_->bounds, kSize, kSize), o);
  for (int k : {1, 4}) {
    const jitter_test::MaskedError off =
        jitter_test::masked_error(render(k, false, kSize), pt, *mask_, 1);
    const jitter_test::MaskedError on =
        jitter_test::masked_error(render(k, true, kSize), pt, *mask_, 1);
    std::printf("k=%d edges against pt (box filter, 1024 spp): rmse off %.4f on %.4f, relmse off "
                "%.4f on %.4f\n",
                k, off.rmse, on.rmse, off.relmse, on.relmse);
    // Measured: edge RMSE 0.326 -> 0.049 (k = 1), 0.330 -> 0.073 (k = 4). The edge relMSE
    // (0.067 -> 0.053, 0.234 -> 0.218) is dominated by the N = 64 VPLs' own error against pt.
    EXPECT_LT(on.rmse, 0.5 * off.rmse) << k;
  }
}

} // namespace IRAD_UNITY_ID
} // namespace irad
