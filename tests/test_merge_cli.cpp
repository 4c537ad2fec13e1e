// irad render --path-range / --spp-range and irad merge through the real command line: the
// parts' headers, the merge, and bad input (one line naming the file or option, exit code 1,
// no output written).
#include "core/image/image_io.h"
#include "tests/test_paths.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace IRAD_UNITY_ID {

struct CliRun {
  int code;
  std::string err;
};

class MergeCli : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("irad_merge_cli_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  CliRun irad(const std::string& args, const std::string& env = "") {
    const fs::path err = dir_ / "stderr.txt";
    const std::string cmd = env + " " + std::string(IRAD_BINARY) + " " + args +
                            " > /dev/null 2> '" + err.string() + "'";
    const int status = std::system(cmd.c_str());
    std::ifstream in(err);
    std::stringstream s;
    s << in.rdbuf();
    return {WEXITSTATUS(status), s.str()};
  }
  std::string scene() const { return std::string(IRAD_SOURCE_DIR) + "/data/cornell_box.gltf"; }
  // Part `name` of the 16x16, N = 8 render with `extra` options.
  fs::path part(const std::string& name, const std::string& range, const std::string& extra = "") {
    const fs::path p = dir_ / name;
    const CliRun r = irad("render " + scene() + " --size 16x16 --paths 8 --gl osmesa --quiet " +
                          range + " " + extra + " -o " + p.string());
    EXPECT_EQ(r.code, 0) << r.err;
    return p;
  }
  void expect_error(const std::string& args, const std::string& needle,
                    const std::string& env = "") {
    const fs::path out = dir_ / "out.exr";
    const CliRun r = irad(args + " -o " + out.string(), env);
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("irad: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(dir_ / "out.exr.tmp"));
  }
  std::string merge(std::initializer_list<fs::path> parts) const {
    std::string args = "merge";
    for (const fs::path& p : parts) args += " " + p.string();
    return args;
  }

  fs::path dir_;
};

TEST_F(MergeCli, PartHeaderSaysWhatItIs) {
  const fs::path p = part("a.exr", "--path-range 2:5");
  irad::ExrAttributes a;
  irad::read_exr(p, &a);
  EXPECT_EQ(a["irad.part.kind"], "paths");
  EXPECT_EQ(a["irad.part.total"], "8");
  EXPECT_EQ(a["irad.part.range"], "2:5");
  EXPECT_EQ(a["irad.scene.fnv1a64"].size(), 16u);
  EXPECT_NE(a["irad.options"].find("--interleave=auto"), std::string::npos) << a["irad.options"];
  EXPECT_EQ(a["irad.options"].find("--threads"), std::string::npos) << a["irad.options"];
  EXPECT_FALSE(a["irad.version"].empty());
}

TEST_F(MergeCli, MergedPartsMatchTheSingleRender) {
  const fs::path a = part("a.exr", "--path-range 0:3"), b = part("b.exr", "--path-range 3:8");
  const fs::path whole = part("whole.exr", "");
  const fs::path out = dir_ / "merged.exr";
  const CliRun r = irad(merge({b, a}) + " -o " + out.string() + " -o " + (dir_ / "m.png").string());
  ASSERT_EQ(r.code, 0) << r.err;
  const irad::Image m = irad::read_exr(out), w = irad::read_exr(whole);
  double worst = 0.0;
  for (std::size_t i = 0; i < w.pixels().size(); ++i)
    for (int c = 0; c < 4; ++c)
      worst = std::max(worst, double(std::abs(m.pixels()[i][c] - w.pixels()[i][c])));
  EXPECT_LE(worst, 1e-5); // docs/cluster.md: measured 2.4e-7 on values up to ~1
  EXPECT_TRUE(fs::exists(dir_ / "m.png"));
}

TEST_F(MergeCli, RangeOutsideOrEmpty) {
  expect_error("render " + scene() + " --paths 8 --path-range 4:9", "--path-range");
  expect_error("render " + scene() + " --paths 8 --path-range 4:4", "--path-range");
  expect_error("render " + scene() + " --estimator pt --spp 4 --spp-range 0:5", "--spp-range");
  expect_error("render " + scene() + " --paths 8 --estimator pt --path-range 0:4",
               "is for raster and rt-vpl");
  expect_error("render " + scene() + " --paths 8 --path-range 0:4 --bias-compensation",
               "--bias-compensation");
  expect_error("render " + scene() + " --paths 8 --path-range auto", "SLURM_ARRAY_TASK_ID");
  // The parts must share one N: --paths auto (the default) chooses it per scene.
  expect_error("render " + scene() + " --path-range 0:4", "--path-range: needs --paths N");
  expect_error("render " + scene() + " --paths 8 --rounds 2 --path-range 0:4", "--rounds");
  expect_error("render " + scene() + " --paths 8 --path-range auto", "--path-range",
               "SLURM_ARRAY_TASK_ID=7 SLURM_ARRAY_TASK_COUNT=4");
}

TEST_F(MergeCli, PartsOfOtherOptionsOrScenes) {
  const fs::path a = part("a.exr", "--path-range 0:4");
  const fs::path b = part("b.exr", "--path-range 4:8", "--clamp 0.1");
  expect_error(merge({a, b}), "b.exr");
  const fs::path copy = dir_ / "box.gltf";
  fs::copy_file(scene(), copy);
  std::ofstream(copy, std::ios::app) << " ";
  const CliRun r = irad("render " + copy.string() +
                        " --size 16x16 --paths 8 --gl osmesa --quiet --path-range 4:8 -o " +
                        (dir_ / "c.exr").string());
  ASSERT_EQ(r.code, 0) << r.err;
  expect_error(merge({a, dir_ / "c.exr"}), "c.exr: does not belong with");
}

TEST_F(MergeCli, MissingOrOverlappingParts) {
  const fs::path a = part("a.exr", "--path-range 0:4"), b = part("b.exr", "--path-range 5:8");
  const fs::path c = part("c.exr", "--path-range 3:8");
  expect_error(merge({a, b}), "b.exr: irad.part.range: 5:8 leaves 4:5 missing");
  expect_error(merge({a, c}), "c.exr: irad.part.range: 3:8 overlaps");
  expect_error(merge({a}), "a.exr: irad.part.range: the parts end at 4");
}

TEST_F(MergeCli, CorruptOrForeignExr) {
  const fs::path a = part("a.exr", "--path-range 0:8");
  const fs::path plain = dir_ / "plain.exr";
  ASSERT_EQ(
      irad("render " + scene() + " --size 16x16 --paths 8 --gl osmesa -o " + plain.string()).code,
      0);
  expect_error(merge({plain}), "plain.exr: irad.part.kind: missing");
  const fs::path broken = dir_ / "broken.exr";
  std::ofstream(broken, std::ios::binary) << "not an EXR";
  expect_error(merge({a, broken}), "broken.exr");
  expect_error(merge({dir_ / "nope.exr"}), "nope.exr");
}

} // namespace
