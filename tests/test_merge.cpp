// Parts of a render (lib/irad/parts.h): path ranges (raster, rt-vpl) and spp ranges (pt) add up
// to the single-process render; merge_parts refuses parts that do not belong together.
#include "core/image/image_io.h"
#include "core/util/error.h"
#include "irad/parts.h"
#include "irad/render.h"
#include "irad/scene_setup.h"
#include "tests/test_paths.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace IRAD_UNITY_ID {

struct Difference {
  double max_abs = 0.0;                    // over R, G, B, A
  double max_rel = 0.0;                    // |a - b| / max(|b|, 1e-3)
  std::size_t differing = 0, channels = 0; // channels whose float bits differ (after rounding)
};

Difference difference(const irad::Image& a, const std::vector<glm::dvec4>& b) {
  Difference d;
  for (std::size_t i = 0; i < b.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      const double e = std::abs(double(a.pixels()[i][c]) - b[i][c]);
      d.max_abs = std::max(d.max_abs, e);
      d.max_rel = std::max(d.max_rel, e / std::max(std::abs(b[i][c]), 1e-3));
      d.differing += a.pixels()[i][c] != static_cast<float>(b[i][c]);
      ++d.channels;
    }
  return d;
}

class Parts : public ::testing::Test {
protected:
  irad::Log log{[](const std::string&) {}};
  irad::Scene scene =
      irad::load_scene(std::string(IRAD_SOURCE_DIR) + "/data/cornell_box.gltf", {}, log);

  irad::RenderOptions options(irad::Estimator estimator) const {
    irad::RenderOptions o;
    o.estimator = estimator;
    o.size = std::pair{32, 32};
    o.walk.paths = 32;
    o.pt.spp = 8;
    o.raster.backend = irad::GlBackend::OsMesa;
    return o;
  }
  // The full render against the double sum of the renders of `ranges` (A, B pairs of paths or
  // samples, covering 0..total); prints the difference (docs/cluster.md quotes it).
  Difference split(irad::RenderOptions o,
                   const std::vector<std::pair<std::uint32_t, std::uint32_t>>& ranges) {
    const irad::Image full = irad::render(scene, o, log).image;
    std::vector<glm::dvec4> sum(full.pixels().size(), glm::dvec4(0.0));
    for (const auto& [a, b] : ranges) {
      if (o.estimator == irad::Estimator::Pt)
        std::tie(o.pt.first_sample, o.pt.end_sample) = std::pair{a, b};
      else
        std::tie(o.walk.first_path, o.walk.end_path) = std::pair{a, b};
      const irad::Image part = irad::render(scene, o, log).image;
      for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += glm::dvec4(part.pixels()[i]);
    }
    const Difference d = difference(full, sum);
    std::printf("parts against the single render: max abs %.3g, max rel %.3g, %zu of %zu "
                "channels differ\n",
                d.max_abs, d.max_rel, d.differing, d.channels);
    return d;
  }
};

const std::vector<std::pair<std::uint32_t, std::uint32_t>> kFour = {
    {0, 8}, {8, 16}, {16, 24}, {24, 32}};

// Bounds: the float framebuffer adds the VPLs in another order and grouping (the parts' sums,
// then their double sum), and the parts after the first subtract the emitters' pass; measured
// max relative differences at 32x32, N = 32 (4 parts): default options 3.0e-7, --interleave 1
// --batch 1 3.5e-7, jitter (3 uneven parts) 3.7e-7, rt-vpl 5.4e-7, pt 9.1e-8; max absolute
// 1.9e-6, one float ulp of the emitter's radiance (docs/cluster.md). 4e-6 is 7 times the
// largest; a wrong weight or a lost or doubled VPL is off by far more (one VPL of 170 changes
// pixels by ~1e-3 relative; a missing part by 0.8, AMissingRangeIsMissingLight).
constexpr double kBound = 4e-6;

TEST_F(Parts, RasterPathRangesAddUpToTheFullRender) {
  EXPECT_LE(split(options(irad::Estimator::Raster), kFour).max_rel, kBound);
}

TEST_F(Parts, ReferenceRasterPathRangesAddUpToTheFullRender) {
  irad::RenderOptions o = options(irad::Estimator::Raster);
  o.raster.interleave = 1;
  o.raster.batch = 1;
  EXPECT_LE(split(o, kFour).max_rel, kBound);
}

// At N = 1024 the local clamp (core/lights/clamp_field.h) is below its cap for most VPLs and
// depends on all N paths: a part takes the field of the full walk, and the screen-space
// compensation's exact samples leave the emitters to the part from 0. Measured: max rel 3.9e-7 (as
// above); with each part's own field the parts differed by up to 0.36 relative (1.1e-2 absolute).
TEST_F(Parts, LocalClampAndCompensationSplitWithTheFullWalksField) {
  irad::RenderOptions o = options(irad::Estimator::Raster);
  o.walk.paths = 1024;
  ASSERT_TRUE(o.local_clamp && o.screen_compensation); // the defaults
  EXPECT_LE(split(o, {{0, 256}, {256, 512}, {512, 768}, {768, 1024}}).max_rel, kBound);
}

TEST_F(Parts, UnevenRangesAndJitterAddUp) {
  irad::RenderOptions o = options(irad::Estimator::Raster);
  o.raster.jitter = true;
  EXPECT_LE(split(o, {{0, 1}, {1, 20}, {20, 32}}).max_rel, kBound);
}

TEST_F(Parts, RtVplPathRangesAddUp) {
  EXPECT_LE(split(options(irad::Estimator::RtVpl), kFour).max_rel, kBound);
}

// pt sums each pixel's samples in double and divides by S once: a range changes only the last
// float rounding of each part.
TEST_F(Parts, PtSppRangesAddUp) {
  EXPECT_LE(split(options(irad::Estimator::Pt), {{0, 3}, {3, 8}}).max_rel, kBound);
}

// A part holds only its range's light: dropping one part leaves light missing.
TEST_F(Parts, AMissingRangeIsMissingLight) {
  const irad::RenderOptions o = options(irad::Estimator::Raster);
  EXPECT_GT(split(o, {{0, 8}, {8, 16}, {16, 24}}).max_rel, 1e-2);
}

TEST_F(Parts, RangesThatCannotSplitExactlyAreRefused) {
  irad::RenderOptions o = options(irad::Estimator::Raster);
  o.walk.first_path = 8;
  o.walk.end_path = 16;
  o.bias_compensation = true;
  EXPECT_THROW(irad::render(scene, o, log), irad::Error);
  o.bias_compensation = false;
  o.estimator = irad::Estimator::Pt;
  EXPECT_THROW(irad::render(scene, o, log), irad::Error);
}

TEST(PartRange, ParsesRangesAndArrayTasks) {
  EXPECT_EQ(irad::parse_part_range("3:7", 10, "--path-range"),
            (std::pair<std::uint32_t, std::uint32_t>{3, 7}));
  EXPECT_THROW(irad::parse_part_range("7:7", 10, "--path-range"), irad::Error);
  EXPECT_THROW(irad::parse_part_range("0:11", 10, "--path-range"), irad::Error);
  EXPECT_THROW(irad::parse_part_range("a:3", 10, "--path-range"), irad::Error);
  ::setenv("SLURM_ARRAY_TASK_ID", "5", 1);
  ::setenv("SLURM_ARRAY_TASK_MIN", "3", 1);
  ::setenv("SLURM_ARRAY_TASK_COUNT", "3", 1);
  // Task 2 of 3 over 10: [floor(20/3), floor(30/3)) = [6, 10).
  EXPECT_EQ(irad::parse_part_range("auto", 10, "--path-range"),
            (std::pair<std::uint32_t, std::uint32_t>{6, 10}));
  ::setenv("SLURM_ARRAY_TASK_ID", "6", 1);
  EXPECT_THROW(irad::parse_part_range("auto", 10, "--path-range"), irad::Error);
  ::unsetenv("SLURM_ARRAY_TASK_ID");
  ::unsetenv("SLURM_ARRAY_TASK_MIN");
  ::unsetenv("SLURM_ARRAY_TASK_COUNT");
  EXPECT_THROW(irad::parse_part_range("auto", 10, "--path-range"), irad::Error);
}

} // namespace
