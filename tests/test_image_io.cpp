// Image files: EXR round trips, half-float EXR input, PNG tone mapping and encoding, errors.
#include "core/image/image.h"
#include "core/image/image_io.h"
#include "core/util/error.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include <sys/resource.h>

// OpenEXR's headers are only on the include path when the test target links OpenEXR::OpenEXR.
#if __has_include(<ImfRgbaFile.h>)
#include <ImfRgbaFile.h>
#define IRAD_TEST_HAVE_OPENEXR 1
#else
#define IRAD_TEST_HAVE_OPENEXR 0
#endif

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

namespace fs = std::filesystem;
using irad::Image;

namespace IRAD_UNITY_ID {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// Each test gets an empty folder of its own, removed afterwards.
class ImageIo : public ::testing::Test {
protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("irad_image_io_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path file(const std::string& name) const { return dir_ / name; }

  fs::path dir_;
};

// The what() of the irad::Error thrown by f, or "" when f does not throw one.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const irad::Error& e) {
    return e.what();
  }
  return "";
}

// Decodes a PNG with stb_image; expects 8-bit RGB without alpha.
std::vector<unsigned char> load_png(const fs::path& path, int& width, int& height) {
  int channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &width, &height, &channels, 0);
  if (data == nullptr) {
    ADD_FAILURE() << "stbi_load failed: " << stbi_failure_reason();
    return {};
  }
  EXPECT_EQ(channels, 3);
  std::vector<unsigned char> bytes(data,
                                   data + static_cast<std::size_t>(width) * height * channels);
  stbi_image_free(data);
  return bytes;
}


TEST_F(ImageIo, ExrRoundTripIsBitExact) {
  const float values[] = {0.0f,
                          -0.0f,
                          1e-40f /* denormal */,
                          std::numeric_limits<float>::min(),
                          1e-30f,
                          0.1f,
                          -0.1f,
                          1.0f,
                          -1.5f,
                          65504.0f,
                          1e20f,
                          -3e38f,
                          std::numeric_limits<float>::max(),
                          kInf,
                          -kInf,
                          0.333333343f};
  Image image(5, 3);
  std::size_t k = 0;
  for (glm::vec4& p : image.pixels())
    for (int c = 0; c < 4; ++c) p[c] = values[k++ % std::size(values)];
  const fs::path path = file("round.exr");
  irad::write_exr(path, Image(2, 2)); // replaced by the next write
  irad::write_exr(path, image);
  EXPECT_FALSE(fs::exists(file("round.exr.tmp")));

  const Image back = irad::read_exr(path);
  ASSERT_EQ(back.width(), 5);
  ASSERT_EQ(back.height(), 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x)
      for (int c = 0; c < 4; ++c)
        EXPECT_EQ(std::bit_cast<std::uint32_t>(back.at(x, y)[c]),
                  std::bit_cast<std::uint32_t>(image.at(x, y)[c]))
            << "pixel " << x << "," << y << " channel " << c;
}

TEST_F(ImageIo, ReadsHalfExrWithoutAlphaAndOffsetDataWindow) {
#if IRAD_TEST_HAVE_OPENEXR
  // Display window 8x8 at the origin; data window 3x2 at (2, 5). No alpha channel in the file.
  const Imath::Box2i display({0, 0}, {7, 7});
  const Imath::Box2i data({2, 5}, {4, 6});
  const fs::path path = file("half.exr");
  Imf::Rgba pixels[2][3];
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      pixels[y][x] =
          Imf::Rgba(half(0.5f * static_cast<float>(x)), half(-2.0f * static_cast<float>(y)),
                    half(x == 2 && y == 1 ? 1024.0f : 0.1f), half(0.25f));
  {
    Imf::RgbaOutputFile out(path.c_str(), display, data, Imf::WRITE_RGB);
    out.setFrameBuffer(&pixels[0][0] - data.min.x - data.min.y * 3, 1, 3);
    out.writePixels(2);
  }
  const Image image = irad::read_exr(path);
  ASSERT_EQ(image.width(), 3);
  ASSERT_EQ(image.height(), 2);
  for (int y = 0; y < 2; ++y) {
    for (int x = 0; x < 3; ++x) {
      const glm::vec4 p = image.at(x, y);
      EXPECT_EQ(p.r, 0.5f * static_cast<float>(x));
      EXPECT_EQ(p.g, -2.0f * static_cast<float>(y));
      EXPECT_EQ(p.b, x == 2 && y == 1 ? 1024.0f : static_cast<float>(half(0.1f)));
      EXPECT_EQ(p.a, 1.0f) << "a file without alpha reads as opaque";
    }
  }
#else
  GTEST_SKIP() << "OpenEXR headers are not on the include path: tests/CMakeLists.txt should link "
                  "irad_tests to OpenEXR::OpenEXR";
#endif
}

TEST_F(ImageIo, ReadingMissingOrNonExrFileThrowsNamingIt) {
  const std::string missing = error_of([&] { irad::read_exr(file("missing.exr")); });
  EXPECT_NE(missing.find("missing.exr"), std::string::npos) << missing;
  EXPECT_NE(missing.find("cannot read"), std::string::npos) << missing;
  EXPECT_EQ(missing.find('\n'), std::string::npos) << missing;

  std::ofstream(file("text.exr")) << "this is not an OpenEXR file\n";
  const std::string text = error_of([&] { irad::read_exr(file("text.exr")); });
  EXPECT_NE(text.find("text.exr"), std::string::npos) << text;
  EXPECT_NE(text.find("cannot read"), std::string::npos) << text;
  EXPECT_EQ(text.find('\n'), std::string::npos) << text;
}

TEST_F(ImageIo, WritingIntoMissingFolderThrowsAndCreatesNothing) {
  const fs::path folder = file("no_such_folder");
  for (const char* name : {"out.exr", "out.png"}) {
    const std::string what = error_of([&] { irad::write_image(folder / name, Image(2, 2)); });
    EXPECT_NE(what.find(name), std::string::npos) << what;
    EXPECT_NE(what.find("does not exist"), std::string::npos) << what;
  }
  EXPECT_FALSE(fs::exists(folder));
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(ImageIo, RefusesToReplaceWhatIsNotARegularFile) {
  for (const char* name : {"taken.exr", "taken.png"}) {
    fs::create_directory(file(name));
    const std::string what = error_of([&] { irad::write_image(file(name), Image(2, 2)); });
    EXPECT_NE(what.find("cannot write"), std::string::npos) << what;
    EXPECT_TRUE(fs::is_directory(file(name)));
    EXPECT_FALSE(fs::exists(file(std::string(name) + ".tmp")));
  }
  EXPECT_NE(error_of([&] { irad::write_exr(file("empty.exr"), Image()); }), "");
  EXPECT_FALSE(fs::exists(file("empty.exr")));
}

TEST_F(ImageIo, WriteFailingMidwayKeepsTheOldFileAndLeavesNoTmp) {
  // Noise does not compress, so a 64 KiB file size limit makes both writers fail part way with
  // EFBIG (SIGXFSZ is ignored meanwhile).
  Image noise(256, 256);
  std::uint32_t state = 1;
  for (glm::vec4& p : noise.pixels())
    for (int c = 0; c < 4; ++c) {
      state = state * 1664525u + 1013904223u;
      p[c] = static_cast<float>(state >> 8) / 16777216.0f;
    }
  for (const char* name : {"old.exr", "old.png"}) {
    irad::write_image(file(name), Image(1, 1));
    const auto old_size = fs::file_size(file(name));
    std::string what;
    {
      rlimit saved{};
      ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
      const auto previous_handler = std::signal(SIGXFSZ, SIG_IGN);
      rlimit limited = saved;
      limited.rlim_cur = 64 * 1024;
      ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &limited), 0);
      what = error_of([&] { irad::write_image(file(name), noise); });
      setrlimit(RLIMIT_FSIZE, &saved);
      std::signal(SIGXFSZ, previous_handler);
    }
    EXPECT_NE(what.find("cannot write"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_EQ(fs::file_size(file(name)), old_size) << "the old file is untouched";
    EXPECT_FALSE(fs::exists(file(std::string(name) + ".tmp")));
  }
}

TEST_F(ImageIo, ToneMapAndSrgbAtKnownPoints) {
  const irad::PngOptions clamp;
  EXPECT_EQ(irad::linear_to_srgb(0.0f), 0.0f);
  EXPECT_EQ(irad::linear_to_srgb(1.0f), 1.0f);
  EXPECT_NEAR(irad::linear_to_srgb(0.5f), 0.7354f, 1e-4f);
  EXPECT_NEAR(irad::linear_to_srgb(0.0031308f), 0.0404500f, 1e-6f);
  EXPECT_NEAR(irad::linear_to_srgb(std::nextafter(0.0031308f, 1.0f)),
              irad::linear_to_srgb(0.0031308f), 1e-6f)
      << "the two pieces meet at the boundary";
  EXPECT_EQ(irad::linear_to_srgb(-1.0f), 0.0f);
  EXPECT_EQ(irad::linear_to_srgb(2.0f), 1.0f);
  EXPECT_EQ(irad::linear_to_srgb(kNaN), 0.0f);

  EXPECT_EQ(irad::tone_map(0.0f, clamp), 0.0f);
  EXPECT_EQ(irad::tone_map(0.25f, clamp), 0.25f);
  EXPECT_EQ(irad::tone_map(3.0f, clamp), 1.0f);
  EXPECT_EQ(irad::tone_map(-1.0f, clamp), 0.0f);
  EXPECT_EQ(irad::tone_map(kNaN, clamp), 0.0f);
  EXPECT_EQ(irad::tone_map(kInf, clamp), 1.0f);
  const irad::PngOptions brighter{1.0f, irad::ToneMap::Clamp};
  EXPECT_EQ(irad::tone_map(0.25f, brighter), 0.5f) << "exposure +1 doubles";
  EXPECT_EQ(irad::tone_map(0.75f, brighter), 1.0f);

  const irad::PngOptions reinhard{0.0f, irad::ToneMap::Reinhard};
  EXPECT_EQ(irad::tone_map(1.0f, reinhard), 0.5f);
  EXPECT_FLOAT_EQ(irad::tone_map(3.0f, reinhard), 0.75f);
  EXPECT_EQ(irad::tone_map(-1.0f, reinhard), 0.0f);
  EXPECT_EQ(irad::tone_map(kInf, reinhard), 1.0f);
  EXPECT_EQ(irad::tone_map(kNaN, reinhard), 0.0f);
  EXPECT_FLOAT_EQ(irad::tone_map(0.5f, irad::PngOptions{1.0f, irad::ToneMap::Reinhard}), 0.5f);
}

TEST_F(ImageIo, PngDecodesToExpectedBytes) {
  // Row 0 is the top row of the PNG; alpha is dropped.
  Image image(3, 2);
  image.at(0, 0) = {0.0f, 1.0f, 0.5f, 0.0f};    // 0, 255, 188 (0.7354 * 255 = 187.5)
  image.at(1, 0) = {2.0f, -1.0f, kNaN, 1.0f};   // clamped: 255, 0, 0
  image.at(2, 0) = {0.001f, 0.18f, kInf, 0.5f}; // 12.92 * 0.001 * 255 = 3.29 -> 3; 118; 255
  image.at(0, 1) = {0.25f, 0.25f, 0.25f, 1.0f}; // 137 (0.5371 * 255 = 136.96)
  image.at(1, 1) = {1.0f, 0.0f, 0.0f, 1.0f};
  image.at(2, 1) = {0.0f, 0.0f, 1.0f, 1.0f};
  const fs::path path = file("out.png");
  irad::write_image(path, image);
  int width = 0, height = 0;
  const std::vector<unsigned char> bytes = load_png(path, width, height);
  ASSERT_EQ(width, 3);
  ASSERT_EQ(height, 2);
  ASSERT_EQ(bytes.size(), 18u);
  const std::vector<unsigned char> expected = {0,   255, 188, 255, 0, 0, 3, 118, 255,
                                               137, 137, 137, 255, 0, 0, 0, 0,   255};
  EXPECT_EQ(bytes, expected);

  // Exposure +1 maps 0.25 to the display value of 0.5; Reinhard maps 0.25 to 0.2 and 1 to 0.5.
  irad::write_png(path, Image(1, 1), {}); // replaced below
  Image grey(1, 1);
  grey.at(0, 0) = {0.25f, 1.0f, 0.0f, 1.0f};
  irad::write_png(path, grey, {1.0f, irad::ToneMap::Clamp});
  EXPECT_EQ(load_png(path, width, height), (std::vector<unsigned char>{188, 255, 0}));
  irad::write_png(path, grey, {0.0f, irad::ToneMap::Reinhard});
  EXPECT_EQ(load_png(path, width, height), (std::vector<unsigned char>{124, 188, 0}));
  EXPECT_FALSE(fs::exists(file("out.png.tmp")));
}

TEST_F(ImageIo, ImageFormatOfUsesTheExtension) {
  EXPECT_EQ(irad::image_format_of("a/b.exr"), irad::ImageFormat::Exr);
  EXPECT_EQ(irad::image_format_of("B.EXR"), irad::ImageFormat::Exr);
  EXPECT_EQ(irad::image_format_of("c.Png"), irad::ImageFormat::Png);
  const std::string jpg = error_of([] { irad::image_format_of("photo.jpg"); });
  EXPECT_NE(jpg.find("photo.jpg"), std::string::npos) << jpg;
  EXPECT_NE(jpg.find("'.jpg'"), std::string::npos) << jpg;
  EXPECT_NE(error_of([] { irad::image_format_of("no_extension"); }), "");
  EXPECT_NE(error_of([] { irad::image_format_of("archive.exr.gz"); }), "");
}

TEST_F(ImageIo, NonFiniteCountCountsPixels) {
  Image image(4, 2);
  EXPECT_EQ(image.non_finite_count(), 0u);
  image.at(0, 0) = {kNaN, 0.0f, 0.0f, 1.0f};
  image.at(1, 0) = {kNaN, kInf, -kInf, 1.0f}; // one pixel, however many channels
  image.at(3, 1) = {0.0f, 0.0f, 0.0f, kNaN};  // alpha counts too
  image.at(2, 1) = {std::numeric_limits<float>::max(), 1e-40f, -1.0f, 1.0f}; // finite
  EXPECT_EQ(image.non_finite_count(), 3u);
  EXPECT_EQ(Image().non_finite_count(), 0u);
}

} // namespace
