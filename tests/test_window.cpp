// irad walkthrough --window through the real command line: a real GLFW window under Xvfb
// (xvfb-run, scripts/setup.sh installs it), its framebuffer read back into a screenshot and
// compared with the headless walkthrough's frame of the same camera; and the one-line error when
// there is no display. Key and mouse handling is tested without a window (test_fly_camera.cpp).
#include "core/image/image.h"
#include "core/image/image_io.h"
#include "tests/test_paths.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <string>

namespace irad {
namespace IRAD_UNITY_ID {

namespace fs = std::filesystem;

struct CliRun {
  int code;
  std::string out, err;
};

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class WindowCli : public ::testing::Test {
protected:
  void SetUp() override {
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::replace(name.begin(), name.end(), '/', '_');
    dir_ = fs::path(::testing::TempDir()) / ("irad_window_" + name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // `prefix` goes before the binary (env, xvfb-run).
  CliRun irad(const std::string& prefix, const std::string& args) {
    const std::string cmd = prefix + " " + IRAD_BINARY + " " + args + " > '" +
                            (dir_ / "out.txt").string() + "' 2> '" + (dir_ / "err.txt").string() +
                            "' < /dev/null";
    const int status = std::system(cmd.c_str());
    return {WEXITSTATUS(status), read_text(dir_ / "out.txt"), read_text(dir_ / "err.txt")};
  }
  static std::string cornell() { return std::string(IRAD_SOURCE_DIR) + "/data/cornell_box.gltf"; }

  fs::path dir_;
};

class WindowGl : public WindowCli, public ::testing::WithParamInterface<const char*> {};

void expect_one_line_error(const CliRun& r, const std::string& needle) {
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_EQ(r.err.rfind("irad: error: --window: no display", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
}

TEST_F(WindowCli, WithoutADisplayFailsWithOneLine) {
  const std::string args = "walkthrough " + cornell() + " --window --window-frames 1";
  expect_one_line_error(irad("env -u DISPLAY -u WAYLAND_DISPLAY", args), "DISPLAY");
  // A display that does not exist: glfwInit fails (GLFW's reason follows on the same line).
  expect_one_line_error(irad("env -u WAYLAND_DISPLAY DISPLAY=:4321", args), "GLFW");
  // Neither frames nor a window: -o is required; window options need --window.
  EXPECT_EQ(irad("", "walkthrough " + cornell()).code, 1);
  EXPECT_EQ(irad("", "walkthrough " + cornell() + " -o x%d.png --window-frames 2").code, 1);
}

// The byte a display shows for a linear value: what write_png and the window both use.
int display_byte(float linear) {
  return static_cast<int>(std::lround(255.0f * linear_to_srgb(tone_map(linear, {}))));
}

// The window's last frame, read back from its framebuffer, against the headless walkthrough's
// frame from the same (untouched) camera. Non-square, so that a flip or transpose would show.
TEST_P(WindowGl, ScreenshotMatchesTheOffscreenFrame) {
  if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "xvfb-run is not installed (scripts/setup.sh installs xvfb and xauth)";
  const std::string gl = GetParam();
  const std::string common = "walkthrough " + cornell() + " --size 96x80 --paths 16 --gl " + gl;
  const fs::path shot = dir_ / "shot.exr";
  // ctest runs the two backends at once: each searches its own range of display numbers, so that
  // two xvfb-run -a cannot race for the same free one.
  const std::string xvfb = gl == "egl" ? "xvfb-run -a -n 160" : "xvfb-run -a -n 140";
  const CliRun w =
      irad(xvfb, common + " --window --window-frames 3 --screenshot '" + shot.string() + "'");
  ASSERT_EQ(w.code, 0) << w.err;
  EXPECT_NE(w.out.find("window, 3 frames, mode cached"), std::string::npos) << w.out;
  const CliRun h = irad("", common + " --mode cached --frames 0:3 -q -o '" +
                                (dir_ / "frame%d.exr").string() + "'");
  ASSERT_EQ(h.code, 0) << h.err;

  const Image s = read_exr(shot);
  const Image f = read_exr(dir_ / "frame2.exr");
  ASSERT_EQ(s.width(), 96); // the window's size
  ASSERT_EQ(s.height(), 80);
  double mean = 0.0;
  int max_diff = 0;
  for (int y = 0; y < s.height(); ++y)
    for (int x = 0; x < s.width(); ++x)
      for (int c = 0; c < 3; ++c) {
        const int a = display_byte(s.at(x, y)[c]), b = display_byte(f.at(x, y)[c]);
        mean += a;
        max_diff = std::max(max_diff, std::abs(a - b));
      }
  mean /= 96.0 * 80.0 * 3.0;
  EXPECT_GT(mean, 25.0); // not black: measured 49.7 (the mean sRGB byte of the Cornell box)
  // Measured: 0 through OSMesa and EGL (the window shows the renderer's bytes unchanged; rows
  // presented top-down instead give 255); 1 allows one rounding step of the sRGB round trip
  // through the EXR screenshot.
  EXPECT_LE(max_diff, 1);
}

INSTANTIATE_TEST_SUITE_P(Gl, WindowGl, ::testing::Values("osmesa", "egl"));

} // namespace
} // namespace irad
