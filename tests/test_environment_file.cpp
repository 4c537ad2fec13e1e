// Environment map files (core/environment/environment_file.h): OpenEXR and Radiance HDR round trips
// with row 0 at the top, and one-line messages for every bad input; the --env colour.
#include "core/environment/environment_file.h"
#include "core/image/image.h"
#include "core/image/image_io.h"
#include "core/util/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <utility>
#include <vector>

// stb_image_write's HDR writer, static in this file.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace fs = std::filesystem;
using irad::Image;

namespace IRAD_UNITY_ID {

// Each test gets an empty folder of its own, removed afterwards.
class EnvironmentFile : public ::testing::Test {
protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("irad_env_file_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path file(const std::string& name) const { return dir_ / name; }

  // Writes `bytes` to the file `name` and returns its path.
  fs::path write_bytes(const std::string& name, const std::string& bytes) const {
    std::ofstream(file(name), std::ios::binary) << bytes;
    return file(name);
  }
  // An RGB Radiance HDR file of `image` (stb_image_write: RLE from width 8 on).
  fs::path write_hdr(const std::string& name, const Image& image) const {
    std::vector<float> rgb;
    for (const glm::vec4& p : image.pixels()) rgb.insert(rgb.end(), {p.r, p.g, p.b});
    EXPECT_NE(stbi_write_hdr(file(name).c_str(), image.width(), image.height(), 3, rgb.data()), 0);
    return file(name);
  }

  fs::path dir_;
};

// The what() of the irad::Error thrown by reading `path`, or "" when it reads.
std::string read_error(const fs::path& path) {
  try {
    irad::read_environment_map(path, "--env");
  } catch (const irad::Error& e) {
    return e.what();
  }
  return "";
}

// A w x h map whose texels differ by position, row 0 the brightest. Every value is a multiple of
// 1/32 within a factor 8 of its texel's largest channel: exact in RGBE (8-bit mantissas under a
// shared exponent).
Image test_map(int w, int h) {
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      image.at(x, y) = glm::vec4(0.25f * float(8 - y % 8), 0.25f * float(1 + x % 4),
                                 0.5f * std::ldexp(1.0f, -(x % 3)), 0.5f);
  return image;
}

// Every what() names the file and the option, on one line.
void expect_message(const fs::path& path, const std::string& message) {
  const std::string what = read_error(path);
  EXPECT_EQ(what.rfind(path.string() + ": --env: ", 0), 0u) << what;
  EXPECT_NE(what.find(message), std::string::npos) << "expected '" << message << "' in: " << what;
  EXPECT_EQ(what.find('\n'), std::string::npos) << what;
}


TEST_F(EnvironmentFile, ExrRoundTripsWithRowZeroAtTheTopAndAlphaOne) {
  const Image map = test_map(8, 4);
  irad::write_exr(file("sky.exr"), map);
  const Image back = irad::read_environment_map(file("sky.exr"), "--env");
  ASSERT_EQ(back.width(), 8);
  ASSERT_EQ(back.height(), 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x)
      EXPECT_EQ(back.at(x, y), glm::vec4(glm::vec3(map.at(x, y)), 1.0f)) << x << "," << y;
  EXPECT_EQ(back.at(0, 0).r, 2.0f); // the top row is the brightest
}

TEST_F(EnvironmentFile, HdrRoundTripsWithRowZeroAtTheTop) {
  for (const auto& [name, w] :
       {std::pair<std::string, int>{"flat.hdr", 4}, {"rle.HDR", 16}, {"sky.pic", 32}}) {
    const Image map = test_map(w, w / 2);
    const Image back = irad::read_environment_map(write_hdr(name, map), "--env");
    ASSERT_EQ(back.width(), w) << name;
    ASSERT_EQ(back.height(), w / 2) << name;
    for (int y = 0; y < back.height(); ++y) {
      for (int x = 0; x < w; ++x) {
        const glm::vec4 want(glm::vec3(map.at(x, y)), 1.0f);
        EXPECT_EQ(back.at(x, y), want) << name << " " << x << "," << y;
      }
    }
  }
}

TEST_F(EnvironmentFile, RefusesMissingFilesFoldersAndExtensions) {
  expect_message(file("none.hdr"), "cannot read: No such file or directory");
  expect_message(file("none.exr"), "cannot read: No such file or directory");
  fs::create_directories(file("folder.exr"));
  expect_message(file("folder.exr"), "cannot read: it is a folder, not a file");
  irad::write_exr(file("sky.png"), test_map(4, 2));
  expect_message(file("sky.png"), "unknown extension '.png' (an environment map is .exr");
  expect_message(write_bytes("sky", "#?RADIANCE\n"), "no extension");
}

TEST_F(EnvironmentFile, RefusesDataThatDoesNotDecode) {
  expect_message(write_bytes("junk.hdr", "this is not an image\n\x01\x02"),
                 "not a Radiance HDR file");
  expect_message(write_bytes("empty.hdr", ""), "not a Radiance HDR file");
  expect_message(write_bytes("junk.exr", "this is not an image\n\x01\x02"), "not an OpenEXR file");
  expect_message(write_bytes("header.exr", std::string("\x76\x2f\x31\x01", 4) + "garbage bytes"),
                 "the OpenEXR header does not decode");
  expect_message(write_bytes("layout.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n+Y 2 +X 4\n"),
                 "an unsupported Radiance HDR layout");
  expect_message(write_bytes("format.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 2 +X 4\n"),
                 "an unsupported Radiance HDR format");

  // A valid EXR (of incompressible texels) cut short in its pixel data.
  Image noise(64, 32);
  unsigned state = 1;
  for (glm::vec4& p : noise.pixels()) {
    state = state * 1103515245u + 12345u;
    p = glm::vec4(float(state % 1000u) / 100.0f);
  }
  irad::write_exr(file("full.exr"), noise);
  std::ifstream in(file("full.exr"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  expect_message(write_bytes("cut.exr", bytes.substr(0, bytes.size() * 9 / 10)),
                 "the OpenEXR pixels do not decode (corrupt or truncated file)");
}

TEST_F(EnvironmentFile, RefusesTruncatedHdrPixels) {
  const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 4\n";
  // Flat (width 4 < 8): exactly 4 bytes per texel; 31 of the 32 bytes are not enough.
  const std::string texels(32, char(0x80));
  EXPECT_EQ(read_error(write_bytes("whole.hdr", header + texels)), "");
  expect_message(write_bytes("cut.hdr", header + texels.substr(0, 31)),
                 "the Radiance HDR file is truncated: 4 x 2 texels need at least 32 bytes of "
                 "pixels, it holds 31");
  // A few bytes that name the largest size: refused before anything is allocated.
  expect_message(write_bytes("huge.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X "
                                         "16384\n\x02\x02\x40"),
                 "16384 x 8192 texels need at least 8552448 bytes of pixels, it holds 3");
  // Run-length coded (stb_image_write, width 16): cut to half its pixels.
  write_hdr("rle.hdr", test_map(16, 8));
  std::ifstream in(file("rle.hdr"), std::ios::binary);
  const std::string rle((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t pixels = rle.find("+X 16\n") + 6;
  expect_message(write_bytes("rle_cut.hdr", rle.substr(0, pixels + 20)),
                 "the Radiance HDR file is truncated");
}

TEST_F(EnvironmentFile, RefusesMapsThatAreNotTwoToOneOrTooWide) {
  irad::write_exr(file("square.exr"), test_map(4, 4));
  expect_message(file("square.exr"),
                 "4 x 4 texels: an equirectangular map is twice as wide as high");
  expect_message(write_hdr("tall.hdr", test_map(6, 4)), "6 x 4 texels: an equirectangular map");
  // The size is refused from the header, before any pixel is decoded (there are none).
  expect_message(
      write_bytes("wide.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8193 +X 16386\n"),
      "16386 x 8193 texels: wider than the limit of 16384 texels");
}

TEST_F(EnvironmentFile, RefusesTheFirstNonFiniteOrNegativeTexel) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  struct Case {
    int x, y;
    glm::vec4 value;
    std::string message;
  };
  const std::vector<Case> cases = {
      {3,
       1,
       {1.0f, nan, 1.0f, 1.0f},
       "texel x 3, y 1 (row 0 at the top) is (1, nan, 1): not a "
       "finite number"},
      {0, 2, {inf, 1.0f, 1.0f, 1.0f}, "texel x 0, y 2 (row 0 at the top) is (inf, 1, 1)"},
      {2,
       0,
       {1.0f, 1.0f, -0.5f, 1.0f},
       "texel x 2, y 0 (row 0 at the top) is (1, 1, -0.5): "
       "radiance cannot be negative"},
  };
  for (const Case& c : cases) {
    Image map = test_map(8, 4);
    map.at(c.x, c.y) = c.value;
    map.at(7, 3) = glm::vec4(-1.0f); // a later bad texel: not the one named
    irad::write_exr(file("bad.exr"), map);
    expect_message(file("bad.exr"), c.message);
  }
  // A negative alpha is no radiance: ignored, and set to 1.
  Image map = test_map(8, 4);
  map.at(1, 1).a = -1.0f;
  irad::write_exr(file("alpha.exr"), map);
  EXPECT_EQ(irad::read_environment_map(file("alpha.exr"), "--env").at(1, 1).a, 1.0f);
}

TEST(EnvColor, ParsesThreeNonNegativeNumbers) {
  EXPECT_EQ(irad::parse_env_color("1,0.5,0", "--env-color"), glm::vec3(1.0f, 0.5f, 0.0f));
  EXPECT_EQ(irad::parse_env_color("0,0,1e-3", "--env-color"), glm::vec3(0.0f, 0.0f, 1e-3f));
  const auto error = [](const std::string& text) -> std::string {
    try {
      irad::parse_env_color(text, "--env-color");
    } catch (const irad::Error& e) {
      return e.what();
    }
    return "";
  };
  const std::string syntax = "is not R,G,B (three finite numbers)";
  EXPECT_EQ(error("0,0,0"), "--env-color: '0,0,0' is black: no light (leave the option out for "
                            "no environment)");
  EXPECT_EQ(error("1,-1,0"), "--env-color: '1,-1,0' is negative: radiance cannot be negative");
  EXPECT_EQ(error("1,2"), "--env-color: '1,2' " + syntax);
  EXPECT_EQ(error("1,2,3,4"), "--env-color: '1,2,3,4' " + syntax);
  EXPECT_EQ(error("a,b,c"), "--env-color: 'a,b,c' " + syntax);
  EXPECT_EQ(error("nan,1,1"), "--env-color: 'nan,1,1' " + syntax);
  EXPECT_EQ(error("1,inf,1"), "--env-color: '1,inf,1' " + syntax);
}

} // namespace
