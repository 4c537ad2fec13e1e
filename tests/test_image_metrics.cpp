// Image comparison metrics on hand-made images with known answers, the false-colour error image,
// and `irad compare` end to end through the built binary.
#include "core/image/image.h"
#include "core/image/image_io.h"
#include "core/image/image_metrics.h"
#include "core/util/error.h"
#include "tests/test_paths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using irad::Image;
using irad::ImageMetrics;
using nlohmann::json;

namespace IRAD_UNITY_ID {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// A w x h image with pixel (x, y) = f(x, y).
Image make(int w, int h, const std::function<glm::vec4(int, int)>& f) {
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) image.at(x, y) = f(x, y);
  return image;
}

Image constant(int w, int h, glm::vec4 v) {
  return make(w, h, [v](int, int) { return v; });
}

glm::vec4 grey(float v) {
  return {v, v, v, 1.0f};
}

// A varied image with values in [0.1, 1.1].
Image ramp(int w, int h) {
  return make(w, h, [](int x, int y) {
    return glm::vec4(0.1f + 0.01f * static_cast<float>(x), 0.2f + 0.02f * static_cast<float>(y),
                     0.1f * static_cast<float>((x + y) % 7), 1.0f);
  });
}

TEST(ImageMetrics, IdenticalImagesGiveZeroErrorAndRatioOne) {
  const Image a = ramp(13, 7);
  const ImageMetrics m = irad::compare_images(a, a);
  EXPECT_EQ(m.rmse, 0.0);
  EXPECT_EQ(m.relmse, 0.0);
  EXPECT_EQ(m.max_abs_error, 0.0);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(m.rmse_rgb[c], 0.0);
    EXPECT_DOUBLE_EQ(m.mean_ratio[c], 1.0);
  }
  EXPECT_EQ(m.nonfinite_a, 0u);
  EXPECT_EQ(m.nonfinite_b, 0u);
  EXPECT_EQ(m.pixels, 13u * 7u);
  EXPECT_EQ(m.samples, 13u * 7u);
  EXPECT_EQ(m.block, 1);
}

TEST(ImageMetrics, ConstantOffset) {
  const Image b = constant(8, 8, grey(0.5f));
  const Image a = constant(8, 8, grey(0.6f));
  const ImageMetrics m = irad::compare_images(a, b);
  EXPECT_NEAR(m.rmse, 0.1, 1e-6);
  EXPECT_NEAR(m.max_abs_error, 0.1, 1e-6);
  EXPECT_NEAR(m.relmse, 0.01 / (0.25 + 0.01), 1e-6);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(m.rmse_rgb[c], 0.1, 1e-6);
    EXPECT_NEAR(m.mean_ratio[c], 1.2, 1e-6);
  }
}

TEST(ImageMetrics, PerChannelOffsets) {
  const Image b = constant(4, 4, grey(0.5f));
  const Image a = constant(4, 4, {0.6f, 0.5f, 0.3f, 1.0f});
  const ImageMetrics m = irad::compare_images(a, b);
  EXPECT_NEAR(m.rmse_rgb[0], 0.1, 1e-6);
  EXPECT_NEAR(m.rmse_rgb[1], 0.0, 1e-6);
  EXPECT_NEAR(m.rmse_rgb[2], 0.2, 1e-6);
  EXPECT_NEAR(m.rmse, std::sqrt((0.01 + 0.04) / 3), 1e-6);
  EXPECT_NEAR(m.max_abs_error, 0.2, 1e-6);
  EXPECT_NEAR(m.mean_ratio[0], 1.2, 1e-6);
  EXPECT_NEAR(m.mean_ratio[1], 1.0, 1e-6);
  EXPECT_NEAR(m.mean_ratio[2], 0.6, 1e-6);
}

// Left half: black reference, a = 0.1: 0.01 / (0 + eps) = 1. Right half: b = 1, a = 1.1:
// 0.01 / 1.01.
TEST(ImageMetrics, RelMseUsesEpsilon) {
  ASSERT_EQ(irad::kRelMseEpsilon, 1e-2);
  const Image b = make(4, 2, [](int x, int) { return grey(x < 2 ? 0.0f : 1.0f); });
  const Image a = make(4, 2, [](int x, int) { return grey(x < 2 ? 0.1f : 1.1f); });
  const ImageMetrics m = irad::compare_images(a, b);
  EXPECT_NEAR(m.relmse, (1.0 + 0.01 / 1.01) / 2, 1e-5);
}

TEST(ImageMetrics, MeanRatioOfBlackReferenceIsInfOrNan) {
  const Image b = constant(3, 3, grey(0.0f));
  const Image a = constant(3, 3, {0.1f, 0.0f, -0.1f, 1.0f});
  const ImageMetrics m = irad::compare_images(a, b);
  EXPECT_EQ(m.mean_ratio[0], std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(m.mean_ratio[1]));
  EXPECT_EQ(m.mean_ratio[2], -std::numeric_limits<double>::infinity());
  EXPECT_NEAR(m.rmse_rgb[0], 0.1, 1e-6);
}

// A NaN in A and an Inf in B, at different pixels, far off otherwise: both pixels are counted
// and left out, so the result equals the comparison of the remaining (all equal) pixels.
TEST(ImageMetrics, NonFinitePixelsAreCountedAndExcluded) {
  const Image b = ramp(6, 5);
  Image a = b;
  a.at(1, 1) = {kNaN, 0.0f, 0.0f, 1.0f};
  a.at(2, 2).w = kNaN; // alpha is not compared
  Image b2 = b;
  b2.at(4, 3) = {0.0f, 0.0f, -kInf, 1.0f};
  a.at(4, 3) = grey(100.0f);
  const ImageMetrics m = irad::compare_images(a, b2);
  EXPECT_EQ(m.nonfinite_a, 1u);
  EXPECT_EQ(m.nonfinite_b, 1u);
  EXPECT_EQ(m.pixels, 30u - 2u);
  EXPECT_EQ(m.samples, 30u - 2u);
  EXPECT_EQ(m.rmse, 0.0);
  EXPECT_EQ(m.max_abs_error, 0.0);
  EXPECT_DOUBLE_EQ(m.mean_ratio[0], 1.0);
}

TEST(ImageMetrics, NoUsablePixelGivesNan) {
  const Image a = constant(2, 2, grey(kNaN));
  const ImageMetrics m = irad::compare_images(a, constant(2, 2, grey(1.0f)));
  EXPECT_EQ(m.nonfinite_a, 4u);
  EXPECT_EQ(m.pixels, 0u);
  EXPECT_EQ(m.samples, 0u);
  EXPECT_TRUE(std::isnan(m.rmse));
  EXPECT_TRUE(std::isnan(m.relmse));
  EXPECT_TRUE(std::isnan(m.max_abs_error));
  EXPECT_TRUE(std::isnan(m.mean_ratio[0]));
}

// a = 0.5 + bias +- d on a checkerboard, b = 0.5. Pixel by pixel the error is sqrt(d^2 + bias^2);
// the means of even blocks drop the noise and keep the bias.
TEST(ImageMetrics, BlocksSeparateNoiseFromBias) {
  const float d = 0.1f;
  const Image b = constant(64, 64, grey(0.5f));
  auto noisy = [d](float bias) {
    return make(64, 64,
                [d, bias](int x, int y) { return grey(0.5f + bias + ((x + y) % 2 ? d : -d)); });
  };
  const ImageMetrics noise1 = irad::compare_images(noisy(0.0f), b, 1);
  const ImageMetrics noise8 = irad::compare_images(noisy(0.0f), b, 8);
  EXPECT_NEAR(noise1.rmse, 0.1, 1e-6);
  EXPECT_NEAR(noise8.rmse, 0.0, 1e-6);
  EXPECT_NEAR(noise8.relmse, 0.0, 1e-9);
  EXPECT_EQ(noise8.samples, 64u);
  EXPECT_EQ(noise8.pixels, 64u * 64u);
  EXPECT_EQ(noise8.block, 8);

  const ImageMetrics bias1 = irad::compare_images(noisy(0.05f), b, 1);
  const ImageMetrics bias8 = irad::compare_images(noisy(0.05f), b, 8);
  EXPECT_NEAR(bias1.rmse, std::sqrt(0.01 + 0.0025), 1e-6);
  EXPECT_NEAR(bias8.rmse, 0.05, 1e-6);
  EXPECT_NEAR(bias8.relmse, 0.0025 / 0.26, 1e-6);
  EXPECT_NEAR(bias8.mean_ratio[1], 1.1, 1e-6);
}

// 5x3 image, K = 2: block columns {0,1}, {2,3}, {4} and rows {0,1}, {2}. a = x, b = 1, so the
// block means of a - b are -0.5, 1.5 and 3 in each block row.
TEST(ImageMetrics, PartialBlocksAverageWhatTheyContain) {
  const Image a = make(5, 3, [](int x, int) { return grey(static_cast<float>(x)); });
  const ImageMetrics m = irad::compare_images(a, constant(5, 3, grey(1.0f)), 2);
  EXPECT_EQ(m.samples, 6u);
  EXPECT_EQ(m.pixels, 15u);
  EXPECT_NEAR(m.rmse, std::sqrt((0.25 + 2.25 + 9.0) / 3), 1e-6);
  EXPECT_NEAR(m.max_abs_error, 3.0, 1e-6);
  EXPECT_NEAR(m.mean_ratio[0], 2.0, 1e-6); // sum of x over 15 pixels = 30
}

// A block mean covers only the pixels finite in both images; a block larger than the image is
// the whole image.
TEST(ImageMetrics, BlocksSkipNonFinitePixels) {
  const Image b = constant(4, 4, grey(1.0f));
  Image a = constant(4, 4, grey(1.0f));
  a.at(0, 0) = grey(kInf);
  const ImageMetrics m = irad::compare_images(a, b, 2);
  EXPECT_EQ(m.samples, 4u);
  EXPECT_EQ(m.pixels, 15u);
  EXPECT_EQ(m.rmse, 0.0);
  const ImageMetrics whole = irad::compare_images(a, b, 1000);
  EXPECT_EQ(whole.samples, 1u);
  EXPECT_EQ(whole.pixels, 15u);
}

TEST(ImageMetrics, SizeMismatchAndBadBlockThrow) {
  const Image a(4, 4), b(4, 5);
  try {
    irad::require_same_size(a, "a.exr", b, "b.exr");
    FAIL() << "no error";
  } catch (const irad::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("a.exr"), std::string::npos) << what;
    EXPECT_NE(what.find("b.exr"), std::string::npos) << what;
    EXPECT_NE(what.find("4x5"), std::string::npos) << what;
  }
  EXPECT_NO_THROW(irad::require_same_size(a, "a.exr", Image(4, 4), "b.exr"));
  EXPECT_THROW(irad::compare_images(a, b), irad::Error);
  EXPECT_THROW(irad::compare_images(a, a, 0), irad::Error);
  EXPECT_THROW(irad::relative_error_image(a, b, {}), irad::Error);
  EXPECT_THROW(irad::relative_error_image(a, a, {0.0, 1}), irad::Error);
  EXPECT_THROW(irad::relative_error_image(a, a, {0.2, 0}), irad::Error);
}

TEST(ImageMetrics, ErrorRampStops) {
  using A = std::array<float, 3>;
  EXPECT_EQ(irad::error_ramp_display(-1.0), (A{0, 0, 0}));
  EXPECT_EQ(irad::error_ramp_display(0.0), (A{0, 0, 0}));
  EXPECT_EQ(irad::error_ramp_display(0.125), (A{0, 0, 0.5f}));
  EXPECT_EQ(irad::error_ramp_display(0.25), (A{0, 0, 1}));
  EXPECT_EQ(irad::error_ramp_display(0.5), (A{0, 1, 0}));
  EXPECT_EQ(irad::error_ramp_display(0.75), (A{1, 1, 0}));
  EXPECT_EQ(irad::error_ramp_display(1.0), (A{1, 0, 0}));
  EXPECT_EQ(irad::error_ramp_display(7.0), (A{1, 0, 0}));
}

// Relative errors 0, max / 8, max / 2 and 2 max, and a NaN pixel; the stored linear values encode
// (through linear_to_srgb, as write_png does) to the ramp's display values.
TEST(ImageMetrics, RelativeErrorImage) {
  const float eps = static_cast<float>(irad::kRelErrorEpsilon);
  const Image b = constant(5, 1, grey(1.0f));
  Image a = b;
  a.at(1, 0) = grey(1.0f + 0.025f * (1.0f + eps)); // e = 0.025 = 0.2 / 8
  a.at(2, 0) = grey(1.0f - 0.1f * (1.0f + eps));   // e = 0.1
  a.at(3, 0) = grey(1.0f + 0.4f * (1.0f + eps));   // e = 0.4, clipped to red
  a.at(4, 0) = {1.0f, kNaN, 1.0f, 1.0f};
  const Image diff = irad::relative_error_image(a, b, {0.2, 1});
  auto display = [&diff](int x) {
    const glm::vec4 p = diff.at(x, 0);
    EXPECT_EQ(p.w, 1.0f);
    return glm::vec3(irad::linear_to_srgb(p.x), irad::linear_to_srgb(p.y),
                     irad::linear_to_srgb(p.z));
  };
  auto near = [](glm::vec3 u, glm::vec3 v) { return glm::length(u - v) < 1e-3f; };
  EXPECT_TRUE(near(display(0), {0, 0, 0}));
  EXPECT_TRUE(near(display(1), {0, 0, 0.5f}));
  EXPECT_TRUE(near(display(2), {0, 1, 0}));
  EXPECT_TRUE(near(display(3), {1, 0, 0}));
  EXPECT_TRUE(near(display(4), {1, 0, 1}));
}

// With blocks, each block is painted with the error of its means: zero-mean noise turns black.
// 5x3 with K = 2: the corner block holds pixel (4, 2) alone and keeps its error.
TEST(ImageMetrics, RelativeErrorImageWithBlocks) {
  const Image b = constant(5, 3, grey(1.0f));
  const Image a = make(5, 3, [](int x, int y) { return grey((x + y) % 2 ? 1.5f : 0.5f); });
  const Image per_pixel = irad::relative_error_image(a, b, {0.2, 1});
  const Image blocks = irad::relative_error_image(a, b, {0.2, 2});
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) {
      EXPECT_EQ(per_pixel.at(x, y), glm::vec4(1, 0, 0, 1)) << x << "," << y;
      const glm::vec4 expected = x < 4 || y < 2 ? glm::vec4(0, 0, 0, 1) : glm::vec4(1, 0, 0, 1);
      EXPECT_EQ(blocks.at(x, y), expected) << x << "," << y;
    }
}

// ---- irad compare through the binary ----

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct CliRun {
  int code;
  std::string out;
  std::string err;
};

class CompareCli : public ::testing::Test {
protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("irad_compare_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  std::string exr(const std::string& name, const Image& image) {
    irad::write_exr(dir_ / name, image);
    return (dir_ / name).string();
  }
  CliRun irad(const std::string& args) {
    const fs::path out = dir_ / "stdout.txt";
    const fs::path err = dir_ / "stderr.txt";
    const std::string cmd = std::string(IRAD_BINARY) + " " + args + " > '" + out.string() +
                            "' 2> '" + err.string() + "'";
    const int status = std::system(cmd.c_str());
    return {WEXITSTATUS(status), read_text(out), read_text(err)};
  }
  // Expects exit code 1 and one stderr line "irad: error: ..." containing `needle`.
  void expect_error(const std::string& args, const std::string& needle) {
    const CliRun r = irad("compare " + args);
    EXPECT_EQ(r.code, 1) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("irad: error: ", 0), 0u) << args << ": " << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << args << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << args << ": " << r.out;
  }

  fs::path dir_;
};

TEST_F(CompareCli, ReportsMetricsAsTextAndJson) {
  Image a = constant(16, 8, grey(0.6f));
  a.at(3, 3) = grey(kNaN);
  const std::string pa = exr("a.exr", a);
  const std::string pb = exr("b.exr", constant(16, 8, {0.5f, 0.5f, 0.0f, 1.0f}));
  const fs::path js = dir_ / "m.json";
  const CliRun r = irad("compare '" + pa + "' '" + pb + "' --json '" + js.string() + "'");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_NE(r.out.find("\nrelmse "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mean_ratio 1.2 1.2 inf\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("nonfinite 1 0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("pixels 127\n"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.rfind("rmse ", 0), 0u) << r.out;

  const json j = json::parse(read_text(js));
  EXPECT_NEAR(j["rmse_rgb"][0].get<double>(), 0.1, 1e-6);
  EXPECT_NEAR(j["rmse_rgb"][2].get<double>(), 0.6, 1e-6);
  EXPECT_NEAR(j["rmse"].get<double>(), std::sqrt((0.01 + 0.01 + 0.36) / 3), 1e-6);
  EXPECT_NEAR(j["relmse"].get<double>(), (2 * 0.01 / 0.26 + 0.36 / 0.01) / 3, 1e-4);
  EXPECT_NEAR(j["mean_ratio"][0].get<double>(), 1.2, 1e-6);
  EXPECT_EQ(j["mean_ratio"][2], "inf");
  EXPECT_NEAR(j["max_abs_error"].get<double>(), 0.6, 1e-6);
  EXPECT_EQ(j["nonfinite"], json({1, 0}));
  EXPECT_EQ(j["pixels"], 127);
  EXPECT_EQ(j["samples"], 127);
  EXPECT_EQ(j["block"], 1);
  EXPECT_EQ(j["size"], json({16, 8}));
  EXPECT_EQ(j["relmse_eps"], 0.01);
  EXPECT_FALSE(fs::exists(dir_ / "m.json.tmp"));
}

TEST_F(CompareCli, BlocksAndDiffImage) {
  const Image b = constant(16, 16, grey(0.5f));
  const Image a = make(16, 16, [](int x, int y) { return grey((x + y) % 2 ? 0.6f : 0.4f); });
  const std::string pa = exr("a.exr", a), pb = exr("b.exr", b);
  const fs::path js = dir_ / "m.json", png = dir_ / "diff.png";
  const CliRun r = irad("compare '" + pa + "' '" + pb + "' --block 4 --diff '" + png.string() +
                        "' --diff-max 0.5 --json '" + js.string() + "'");
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(read_text(js));
  EXPECT_NEAR(j["rmse"].get<double>(), 0.0, 1e-6);
  EXPECT_EQ(j["samples"], 16);
  EXPECT_EQ(j["pixels"], 256);
  EXPECT_EQ(j["block"], 4);
  // A PNG of the input's size: signature, then the IHDR chunk with big-endian width and height.
  const std::string bytes = read_text(png);
  ASSERT_GE(bytes.size(), 24u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  auto be32 = [&bytes](std::size_t i) {
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(bytes[i + k]);
    return v;
  };
  EXPECT_EQ(be32(16), 16u);
  EXPECT_EQ(be32(20), 16u);
}

TEST_F(CompareCli, BadInputsGiveOneLineAndCodeOne) {
  const std::string pa = exr("a.exr", constant(8, 8, grey(0.5f)));
  const std::string pb = exr("b.exr", constant(8, 8, grey(0.5f)));
  const std::string small = exr("small.exr", constant(8, 4, grey(0.5f)));
  std::ofstream(dir_ / "text.exr") << "not an image\n";
  const std::string text = (dir_ / "text.exr").string();
  const std::string ab = "'" + pa + "' '" + pb + "' ";

  expect_error("'" + (dir_ / "missing.exr").string() + "' '" + pb + "'", "missing.exr");
  expect_error("'" + pa + "' '" + (dir_ / "missing.exr").string() + "'", "missing.exr");
  expect_error("'" + text + "' '" + pb + "'", "text.exr");
  expect_error("'" + small + "' '" + pb + "'", "small.exr");
  expect_error("'" + small + "' '" + pb + "'", "b.exr");
  expect_error(ab + "--block 0", "--block");
  expect_error(ab + "--block -2", "--block");
  expect_error(ab + "--diff-max 0", "--diff-max");
  expect_error(ab + "--diff '" + (dir_ / "no/dir/d.png").string() + "'", "no/dir");
  expect_error(ab + "--diff '" + (dir_ / "d.jpg").string() + "'", "d.jpg");
  expect_error(ab + "--json '" + (dir_ / "no/dir/m.json").string() + "'", "no/dir");
  expect_error(ab + "--json '" + dir_.string() + "'", "not a regular file");
  expect_error("'" + pa + "'", "reference");
  EXPECT_FALSE(fs::exists(dir_ / "d.jpg"));
}

} // namespace
