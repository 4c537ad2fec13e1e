// Matrix row-column sampling (core/lights/light_clusters.h, walk/vpls/light_rows.h): the clustering
// on hand-made matrices whose best clusters are known, the representatives' expectation, and the
// clustered estimate against the very same VPLs summed exactly by rt-vpl (its error measured).
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/image/image_metrics.h"
#include "core/lights/light_clusters.h"
#include "core/util/error.h"
#include "irad/render.h"
#include "raster/raster_renderer.h"
#include "tests/test_paths.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/vpls/light_rows.h"
#include "walk/vpls/quasi_random_walk.h"

#include <algorithm>
#include <filesystem>
#include <gtest/gtest.h>
#include <set>

namespace irad {
namespace IRAD_UNITY_ID {

// Columns j < n lit only rows [0, 4), columns j >= n only rows [4, 8), with norms 1 + j.
ReducedMatrix two_groups(std::size_t n) {
  ReducedMatrix m;
  m.rows = 8;
  m.columns = 2 * n;
  m.values.assign(m.rows * m.columns, 0.0f);
  for (std::size_t j = 0; j < m.columns; ++j)
    for (std::size_t i = 0; i < 4; ++i)
      m.column(j)[(j < n ? 0 : 4) + i] = 0.5f * float(1 + j) * (1.0f + 0.01f * float(i));
  return m;
}

VplSet vpls_for(std::size_t count) {
  VplSet set;
  set.paths = 1;
  for (std::size_t j = 0; j < count; ++j) {
    Vpl v;
    v.position = glm::vec3(float(j), 0.0f, 0.0f);
    v.intensity = glm::vec3(1.0f + float(j), 2.0f, 0.5f * float(j));
    set.vpls.push_back(v);
  }
  return set;
}

TEST(LightClusters, TwoClustersSeparateColumnsThatLightDisjointPixels) {
  const ReducedMatrix m = two_groups(10);
  const ColumnClusters c = cluster_columns(m, 2, 3);
  ASSERT_EQ(c.clusters(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    std::set<bool> groups;
    for (std::uint32_t i = c.starts[k]; i < c.starts[k + 1]; ++i) groups.insert(c.order[i] < 10);
    EXPECT_EQ(groups.size(), 1u) << "cluster " << k << " mixes the two groups";
  }
}

TEST(LightClusters, ColumnsNoRowSeesAreDroppedAndFewColumnsStayThemselves) {
  ReducedMatrix m = two_groups(3);
  for (std::size_t i = 0; i < m.rows; ++i) m.column(4)[i] = 0.0f; // VPL 4: seen by no row
  const ColumnClusters c = cluster_columns(m, 100, 1);
  EXPECT_EQ(c.clusters(), 5u);
  const VplSet walk = vpls_for(6);
  const Representatives r = pick_representatives(walk, c, 7);
  ASSERT_EQ(r.set.vpls.size(), 5u);
  for (const Vpl& v : r.set.vpls) { // every cluster a single VPL: drawn as it is
    const Vpl& w = walk.vpls[static_cast<std::size_t>(v.position.x)];
    EXPECT_EQ(v.intensity, w.intensity);
  }
  const double all = 21.0 + 6 * 2.0 + 0.5 * 15.0; // the VPLs' r + g + b
  EXPECT_NEAR(r.dropped_fraction, (5.0 + 2.0 + 2.0) / all, 1e-9);
}

// E[representative] = the cluster's sum: the mean over many draws of the representatives'
// total intensity against the walk's (the clustering fixed, only the draw's seed changes).
TEST(LightClusters, RepresentativesAreUnbiased) {
  const ReducedMatrix m = two_groups(20);
  const ColumnClusters c = cluster_columns(m, 6, 5);
  ASSERT_EQ(c.clusters(), 6u);
  const VplSet walk = vpls_for(40);
  glm::dvec3 exact(0.0);
  for (const Vpl& v : walk.vpls) exact += glm::dvec3(v.intensity);
  glm::dvec3 mean(0.0);
  const int draws = 4000;
  for (int s = 0; s < draws; ++s)
    for (const Vpl& v : pick_representatives(walk, c, std::uint64_t(s)).set.vpls)
      mean += glm::dvec3(v.intensity) / double(draws);
  // Measured: within 0.3 % at 4000 draws (the draw's spread: a few % per draw).
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(mean[ch] / exact[ch], 1.0, 0.01) << "channel " << ch;
}

TEST(LightClusters, MoreClustersCostLess) {
  ReducedMatrix m = two_groups(50);
  for (std::size_t j = 0; j < m.columns; ++j) m.column(j)[j % m.rows] += 0.3f * float(j % 7);
  double previous = std::numeric_limits<double>::infinity();
  for (std::size_t k : {1u, 2u, 8u, 32u}) {
    const ColumnClusters c = cluster_columns(m, k, 9);
    EXPECT_EQ(c.clusters(), k);
    double cost = 0.0; // sum over clusters of 2 (alpha_C^2 - |S_C|^2)
    for (std::size_t q = 0; q < c.clusters(); ++q) {
      std::vector<double> s(m.rows, 0.0);
      double alpha = 0.0;
      for (std::uint32_t i = c.starts[q]; i < c.starts[q + 1]; ++i) {
        alpha += c.norms[c.order[i]];
        for (std::size_t r = 0; r < m.rows; ++r) s[r] += m.column(c.order[i])[r];
      }
      double s2 = 0.0;
      for (double v : s) s2 += v * v;
      cost += 2.0 * (alpha * alpha - s2);
    }
    EXPECT_LT(cost, previous) << k << " clusters";
    previous = cost;
  }
}

Log quiet_log() {
  return Log([](const std::string&) {});
}

// The Cornell box at 48x48 and its ray-tracing structure.
class CornellClusters : public ::testing::Test {
protected:
  Log log = quiet_log();
  const Scene scene =
      load_gltf(std::filesystem::path(IRAD_SOURCE_DIR) / "data/cornell_box.gltf", log);
  const RayScene rays{scene};
  const View view = make_view(scene.cameras.at(0), scene.bounds, 48, 48);
  const VplTracerOptions traced{RasterOptions{}.clamp, 0};
};

// The Cornell box's VPLs (N = 512, ~950) as 128 representatives with rt-vpl, against rt-vpl on
// every VPL: the clustering's own error, and the mean of independent draws converging to it.
TEST_F(CornellClusters, CornellRepresentativesEstimateEveryVpl) {
  const VplSet vpls = quasi_random_walk(scene, rays, {512, 64}, log);
  const Image exact = trace_vpls(scene, rays, view, vpls, traced);
  ReducedMatrix m = light_rows(scene, rays, view, vpls, {128, traced.clamp, 0, 0, nullptr});
  EXPECT_GT(m.rows, 120u); // the camera sees the box everywhere (a few rows miss the opening)
  weight_rows_by_inverse_total(m);
  const ColumnClusters c = cluster_columns(m, 128, 0);
  EXPECT_EQ(c.clusters(), 128u);
  Image mean(view.width, view.height);
  const int draws = 8;
  double single = 0.0, dropped = 0.0;
  for (int s = 0; s < draws; ++s) {
    const Representatives r = pick_representatives(vpls, c, std::uint64_t(s));
    dropped = r.dropped_fraction;
    const Image one = trace_vpls(scene, rays, view, r.set, traced);
    single += compare_images(one, exact).relmse / draws;
    for (std::size_t i = 0; i < one.pixels().size(); ++i)
      mean.pixels()[i] += one.pixels()[i] / float(draws);
  }
  const ImageMetrics averaged = compare_images(mean, exact);
  std::printf("cornell N = 512: %zu VPLs as 128 clusters: relMSE %.3g per draw, %.3g for the "
              "mean of %d draws, mean ratio %.4f, dropped %.4f\n",
              vpls.vpls.size(), single, averaged.relmse, draws, averaged.mean_ratio[1], dropped);
  // Measured: relMSE 2.3e-3 per draw; the mean of 8 draws 2.7e-4 (about 1/8: the draws are
  // independent and unbiased), mean ratio 1.005, nothing dropped.
  EXPECT_LT(single, 0.05);
  EXPECT_LT(averaged.relmse, 0.3 * single);
  EXPECT_NEAR(averaged.mean_ratio[1], 1.0, 0.01);
}

// The rows trace the VPLs in a spatial order of their own (walk/vpls/light_rows.cpp), but each
// VPL's term lands in its own column: the VPLs reversed give the same columns reversed, bit for
// bit.
TEST_F(CornellClusters, EachVplsTermLandsInItsOwnColumn) {
  const VplSet vpls = quasi_random_walk(scene, rays, {256, 64}, log);
  VplSet reversed = vpls;
  std::reverse(reversed.vpls.begin(), reversed.vpls.end());
  const LightRowsOptions o{64, traced.clamp, 0, 0, nullptr};
  const ReducedMatrix a = light_rows(scene, rays, view, vpls, o);
  const ReducedMatrix b = light_rows(scene, rays, view, reversed, o);
  ASSERT_EQ(a.columns, vpls.vpls.size());
  ASSERT_EQ(b.rows, a.rows);
  std::size_t lit = 0;
  for (std::size_t j = 0; j < a.columns; ++j)
    for (std::size_t i = 0; i < a.rows; ++i) {
      ASSERT_EQ(a.column(j)[i], b.column(a.columns - 1 - j)[i]) << j << ' ' << i;
      lit += a.column(j)[i] > 0.0f;
    }
  EXPECT_GT(lit, a.rows * a.columns / 4); // most of the box sees most VPLs
}

// The representatives are ordinary VPLs: the raster draws them as rt-vpl sums them.
TEST_F(CornellClusters, RasterDrawsTheRepresentativesAsRtVplSumsThem) {
  const VplSet vpls = quasi_random_walk(scene, rays, {256, 64}, log);
  ReducedMatrix m = light_rows(scene, rays, view, vpls, {64, traced.clamp, 0, 0, nullptr});
  const Representatives r = pick_representatives(vpls, cluster_columns(m, 48, 0), 0);
  RasterOptions k1;
  k1.interleave = 1;
  const Image raster = RasterRenderer(scene, k1).render(view, r.set);
  const ImageMetrics e = compare_images(raster, trace_vpls(scene, rays, view, r.set, traced));
  std::printf("48 representatives: raster vs rt-vpl relMSE %.3g, mean %.5f\n", e.relmse,
              e.mean_ratio[1]);
  // Measured: relMSE 9.0e-4, mean 0.9975 (tests/test_clamp_field.cpp: 2.3e-4 on all VPLs at
  // 64x64; here 48 VPLs with 48x48 pixels).
  EXPECT_LT(e.relmse, 2e-3);
  EXPECT_NEAR(e.mean_ratio[1], 1.0, 0.005);
}

// What `irad render --clusters` does: the default raster (k = 4, local clamp, screen
// compensation) over 256 representatives of N = 2048 paths' VPLs, against rt-vpl over all of
// them; a path range refuses the clustering.
TEST(LightClusters, RenderDrawsTheRepresentatives) {
  Log log = quiet_log();
  const Scene scene =
      load_gltf(std::filesystem::path(IRAD_SOURCE_DIR) / "data/cornell_box.gltf", log);
  RenderOptions all;
  all.size = std::pair{48, 48};
  all.walk.paths = 2048;
  all.estimator = Estimator::RtVpl;
  RenderOptions clustered = all;
  clustered.estimator = Estimator::Raster;
  clustered.clusters = 256;
  const RenderResult a = render(scene, all, log), c = render(scene, clustered, log);
  EXPECT_EQ(c.vpls.vpls.size(), 256u);
  EXPECT_EQ(c.walk_vpls, a.vpls.vpls.size());
  EXPECT_GT(c.seconds.cluster, 0.0);
  const ImageMetrics e = compare_images(c.image, a.image, 4);
  std::printf("%zu VPLs as 256 representatives against all with rt-vpl: 4x4 relMSE %.3g, "
              "mean %.4f\n",
              c.walk_vpls, e.relmse, e.mean_ratio[1]);
  // Measured: 3815 VPLs, 4x4 relMSE 2.5e-3, mean 0.9976 (the clustering's error plus the
  // raster's and the compensation's against the exact sum).
  EXPECT_LT(e.relmse, 5e-3);
  EXPECT_NEAR(e.mean_ratio[1], 1.0, 0.02);
  clustered.walk.first_path = 1024;
  EXPECT_THROW(render(scene, clustered, log), Error);
}

} // namespace IRAD_UNITY_ID
} // namespace irad
