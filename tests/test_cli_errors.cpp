// Bad input through the real command line: one line on stderr naming the file and the element,
// exit code 1, no output file written.
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/image/image_io.h"
#include "tests/test_paths.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using nlohmann::json;

namespace IRAD_UNITY_ID {

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream(p, std::ios::binary) << text;
}

// Minimal base64 for the test's own buffer edits.
const std::string b64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
std::string decode64(const std::string& in) {
  std::string out;
  int val = 0, bits = -8;
  for (unsigned char c : in) {
    const auto pos = b64.find(static_cast<char>(c));
    if (pos == std::string::npos) break;
    val = (val << 6) + static_cast<int>(pos);
    bits += 6;
    if (bits >= 0) {
      out.push_back(static_cast<char>((val >> bits) & 0xff));
      bits -= 8;
    }
  }
  return out;
}
std::string encode64(const std::string& in) {
  std::string out;
  int val = 0, bits = -6;
  for (unsigned char c : in) {
    val = (val << 8) + c;
    bits += 8;
    while (bits >= 0) {
      out.push_back(b64[(val >> bits) & 0x3f]);
      bits -= 6;
    }
  }
  if (bits > -6) out.push_back(b64[((val << 8) >> (bits + 8)) & 0x3f]);
  while (out.size() % 4) out.push_back('=');
  return out;
}

struct CliRun {
  int code;
  std::string err;
};

class CliErrors : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("irad_cli_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    cornell_ = json::parse(read_text(fs::path(IRAD_SOURCE_DIR) / "data/cornell_box.gltf"));
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path scene(const std::string& name, const json& j) {
    const fs::path p = dir_ / name;
    write_text(p, j.dump());
    return p;
  }
  CliRun irad(const std::string& args) {
    const fs::path err = dir_ / "stderr.txt";
    const std::string cmd =
        std::string(IRAD_BINARY) + " " + args + " > /dev/null 2> '" + err.string() + "'";
    const int status = std::system(cmd.c_str());
    return {WEXITSTATUS(status), read_text(err)};
  }
  // Renders `scene_file` to out.png and expects the one-line error containing each of `needles`.
  void expect_error(const std::string& args, std::initializer_list<std::string> needles) {
    const fs::path out = dir_ / "out.png";
    const CliRun r = irad("render " + args + " -o '" + out.string() + "' --paths 4 --size 16x16");
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("irad: error: ", 0), 0u) << r.err;
    for (const std::string& n : needles) EXPECT_NE(r.err.find(n), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(dir_ / "out.png.tmp"));
  }

  fs::path dir_;
  json cornell_;
};

TEST_F(CliErrors, MissingFile) {
  expect_error((dir_ / "nope.gltf").string(), {"nope.gltf"});
}

TEST_F(CliErrors, BrokenJson) {
  const fs::path p = dir_ / "broken.gltf";
  write_text(p, cornell_.dump().substr(0, 200));
  expect_error(p.string(), {"broken.gltf"});
}

TEST_F(CliErrors, WrongVersion) {
  cornell_["asset"]["version"] = "1.0";
  expect_error(scene("v1.gltf", cornell_).string(), {"v1.gltf", "version"});
}

TEST_F(CliErrors, AccessorOutOfRange) {
  cornell_["accessors"][0]["count"] = 100000;
  expect_error(scene("acc.gltf", cornell_).string(), {"acc.gltf", "accessors"});
}

TEST_F(CliErrors, IndexOutOfRange) {
  // Shrink a POSITION accessor below the indices that use it.
  const int position = cornell_["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
  const int normal = cornell_["meshes"][0]["primitives"][0]["attributes"]["NORMAL"];
  cornell_["accessors"][position]["count"] = 2;
  cornell_["accessors"][normal]["count"] = 2;
  expect_error(scene("index.gltf", cornell_).string(), {"index.gltf", "indices"});
}

TEST_F(CliErrors, NanPosition) {
  const std::string prefix = "data:application/octet-stream;base64,";
  std::string uri = cornell_["buffers"][0]["uri"];
  ASSERT_EQ(uri.rfind(prefix, 0), 0u);
  std::string bytes = decode64(uri.substr(prefix.size()));
  const int position = cornell_["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
  const json& acc = cornell_["accessors"][position];
  const json& view = cornell_["bufferViews"][acc["bufferView"].get<int>()];
  const std::size_t offset = view.value("byteOffset", 0) + acc.value("byteOffset", 0);
  const float nan = std::nanf("");
  std::memcpy(bytes.data() + offset, &nan, sizeof nan);
  cornell_["buffers"][0]["uri"] = prefix + encode64(bytes);
  // Not an error: the two floor triangles using the vertex are dropped, with one warning for the
  // file, one naming the accessor and its repair, and one for the accessor's declared max, which
  // the NaN made differ from the data's; the rest renders.
  const fs::path out = dir_ / "out.exr";
  const CliRun r = irad("render " + scene("nan.gltf", cornell_).string() + " -o '" + out.string() +
                        "' --estimator rt-vpl --paths 4 --size 16x16");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out));
  const std::string warning = "irad: warning: ";
  EXPECT_EQ(r.err.rfind(warning, 0), 0u) << r.err;
  EXPECT_NE(r.err.find("nan.gltf: 2 triangle(s) with a NaN or Inf vertex position dropped"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("is NaN or infinite; triangles with a NaN or Inf vertex are dropped"),
            std::string::npos)
      << r.err;
  std::size_t warnings = 0;
  for (std::size_t at = 0; (at = r.err.find(warning, at)) != std::string::npos; ++at) ++warnings;
  EXPECT_EQ(warnings, 3u) << r.err;
}

TEST_F(CliErrors, NoLight) {
  for (json& m : cornell_["materials"]) {
    m.erase("emissiveFactor");
    m.erase("extensions");
  }
  // Unlit scenes get the white environment unless --env none refuses them.
  expect_error(scene("dark.gltf", cornell_).string() + " --env none",
               {"dark.gltf", "--env none", "no light"});
}

// Environment options (core/environment/lighting.h, core/environment/environment_file.h,
// core/environment/sky.h): one line naming the option (and the map), exit code 1, no output.
TEST_F(CliErrors, EnvironmentOptions) {
  const std::string box = std::string(IRAD_SOURCE_DIR) + "/data/cornell_box.gltf";
  const auto map = [&](const char* name, int w, int h, glm::vec4 texel) {
    irad::Image image(w, h);
    for (glm::vec4& p : image.pixels()) p = glm::vec4(1.0f);
    image.at(w - 1, h - 1) = texel;
    const fs::path path = dir_ / name;
    irad::write_exr(path, image);
    return path.string();
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const struct {
    std::string args;
    std::vector<std::string> needles;
  } cases[] = {
      {"--env " + (dir_ / "none.exr").string(), {"none.exr", "--env"}},
      {"--env " + map("square.exr", 8, 8, glm::vec4(1)), {"square.exr", "--env", "8 x 8"}},
      {"--env " + map("nan.exr", 8, 4, glm::vec4(nan)), {"nan.exr", "--env", "x 7, y 3", "finite"}},
      {"--env " + map("negative.exr", 8, 4, glm::vec4(-1)),
       {"negative.exr", "--env", "x 7, y 3", "negative"}},
      {"--env " + (dir_ / "sky.png").string(), {"sky.png", "--env"}},
      {"--sky 91", {"--sky", "91"}},
      {"--sky -90.5", {"--sky", "-90.5"}},
      {"--sky 30,0,1", {"--sky", "turbidity"}},
      {"--sky 30,0,11", {"--sky", "turbidity"}},
      {"--sky 30,x", {"--sky"}},
      {"--sky 30 --env-color 1,1,1", {"--env-color", "--sky"}},
      {"--env-color 1,1", {"--env-color"}},
      {"--env-color 1,-1,1", {"--env-color"}},
      {"--env-strength -1 --env-color 1,1,1", {"--env-strength"}},
  };
  std::ofstream(dir_ / "sky.png") << "not a map";
  for (const auto& c : cases) {
    SCOPED_TRACE(c.args);
    const fs::path out = dir_ / "out.png";
    const CliRun r =
        irad("render " + box + " " + c.args + " -o '" + out.string() + "' --paths 4 --size 16x16");
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("irad: error: ", 0), 0u) << r.err;
    for (const std::string& n : c.needles) EXPECT_NE(r.err.find(n), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST_F(CliErrors, ImpossibleOptions) {
  const std::string box = std::string(IRAD_SOURCE_DIR) + "/data/cornell_box.gltf";
  for (const char* opt : {"--paths 0", "--size 0x0", "--size 12", "--clamp -1", "--shadow-res -1",
                          "--interleave 0", "--camera 7", "--scene 3", "--scene nowhere"}) {
    const fs::path out = dir_ / "o.exr";
    const CliRun r = irad("render " + box + " -o '" + out.string() + "' " + std::string(opt));
    EXPECT_EQ(r.code, 1) << opt << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << opt << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << opt;
  }
}

TEST_F(CliErrors, SceneChoosesAGltfScene) {
  // Two glTF scenes: "box" is the Cornell box, "empty" holds none of its nodes.
  json doc = cornell_;
  doc["scenes"] = {{{"name", "box"}, {"nodes", doc["scenes"][0]["nodes"]}}, {{"name", "empty"}}};
  doc["scene"] = 0;
  const std::string file = scene("two.gltf", doc).string();
  const fs::path out = dir_ / "o.exr";
  const std::string common = " -o '" + out.string() + "' --estimator rt-vpl --paths 4 --size 8x8";
  EXPECT_EQ(irad("render " + file + common + " --scene box").code, 0);
  EXPECT_EQ(irad("render " + file + common + " --scene 0").code, 0);
  const CliRun r = irad("render " + file + common + " --scene empty");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("two.gltf: no triangles"), std::string::npos) << r.err;
  const CliRun missing = irad("render " + file + common + " --scene third");
  EXPECT_NE(missing.err.find("two.gltf: scenes: no scene named or numbered 'third' (2 scenes)"),
            std::string::npos)
      << missing.err;
}

TEST_F(CliErrors, OutputFolderMissingOrBadType) {
  const std::string box = std::string(IRAD_SOURCE_DIR) + "/data/cornell_box.gltf";
  CliRun r = irad("render " + box + " -o '" + (dir_ / "no/such/dir/x.png").string() + "'");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("no/such/dir"), std::string::npos) << r.err;
  r = irad("render " + box + " -o '" + (dir_ / "x.jpg").string() + "'");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("x.jpg"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.jpg"));
}

// --look-from/--look-at/--up/--yfov: one line naming the option, nothing written.
TEST_F(CliErrors, LookAtCamera) {
  const std::string box = std::string(IRAD_SOURCE_DIR) + "/data/cornell_box.gltf ";
  expect_error(box + "--look-from 0,0,1", {"--look-at", "missing"});
  expect_error(box + "--look-at 0,0,1", {"--look-from", "missing"});
  expect_error(box + "--up 0,0,1", {"--look-from", "missing"});
  expect_error(box + "--look-from 1,2 --look-at 0,0,0", {"--look-from", "X,Y,Z"});
  expect_error(box + "--look-from 0,0,1 --look-at 0,0,x", {"--look-at", "X,Y,Z"});
  expect_error(box + "--look-from 0,0,1 --look-at 0,0,0 --up 0,nan,1", {"--up", "X,Y,Z"});
  expect_error(box + "--look-from 1,2,3 --look-at 1,2,3", {"--look-at", "equals --look-from"});
  expect_error(box + "--look-from 0,1,0 --look-at 0,0,0", {"--up", "parallel"});
  expect_error(box + "--look-from 0,0,1 --look-at 0,0,0 --up 0,0,-2", {"--up", "parallel"});
  expect_error(box + "--look-from 0,0,1 --look-at 0,0,0 --up 0,0,0", {"--up", "zero"});
  for (const char* yfov : {"0", "180", "-5", "200", "wide"})
    expect_error(box + "--look-from 0,0,1 --look-at 0,0,0 --yfov " + yfov, {"--yfov"});
  expect_error(box + "--camera 0 --look-from 0,0,1 --look-at 0,0,0", {"--look-from", "--camera"});
  const CliRun r = irad("walkthrough " + box + "-o '" + (dir_ / "f%d.png").string() +
                        "' --frames 0:1 --camera 0 --look-from 0,0,1 --look-at 0,0,0");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("--look-from: cannot be combined with --camera"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "f0.png"));
}

// A --look-from camera placed where the file's camera is gives the very same image as --camera:
// the Cornell box's camera (at (0.278, 0.273, -0.8), turned 180 degrees about y, so looking down
// +z) with the default yfov of 39.6 degrees, no aspect ratio and the near plane irad fits.
TEST_F(CliErrors, LookAtCameraEqualsTheFilesCamera) {
  // glTF requires znear; the file's is the near plane make_view fits for a camera without one.
  irad::Log quiet([](const std::string&) {});
  const irad::Scene loaded =
      irad::load_gltf(std::string(IRAD_SOURCE_DIR) + "/data/cornell_box.gltf", quiet);
  irad::Camera fitted = loaded.cameras.at(0);
  fitted.znear = 0.0f;
  const float znear = irad::make_view(fitted, loaded.bounds, 24, 24).znear;
  cornell_["cameras"][0]["perspective"] = {{"yfov", static_cast<double>(glm::radians(39.6f))},
                                           {"znear", static_cast<double>(znear)}};
  const std::string box = scene("box.gltf", cornell_).string();
  const std::string common = " --estimator rt-vpl --paths 16 --size 24x24 --quiet";
  const fs::path by_name = dir_ / "camera.exr", by_look = dir_ / "look.exr";
  CliRun r = irad("render " + box + " -o '" + by_name.string() + "' --camera 0" + common);
  ASSERT_EQ(r.code, 0) << r.err;
  r = irad("render " + box + " -o '" + by_look.string() +
           "' --look-from 0.278,0.273,-0.8 --look-at 0.278,0.273,0" + common);
  ASSERT_EQ(r.code, 0) << r.err;
  const irad::Image a = irad::read_exr(by_name), b = irad::read_exr(by_look);
  ASSERT_EQ(a.pixels().size(), b.pixels().size());
  EXPECT_TRUE(a.pixels() == b.pixels()) << "the images differ";
  double sum = 0.0;
  for (const auto& p : a.pixels()) sum += p.r;
  EXPECT_GT(sum, 0.0) << "a black image proves nothing";
  // A different viewpoint gives a different image (the option is not ignored).
  r = irad("render " + box + " -o '" + by_look.string() +
           "' --look-from 0.278,0.273,-0.8 --look-at 0.3,0.2,0 --up 0.1,1,0" + common);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(a.pixels() == irad::read_exr(by_look).pixels());
}

// irad walkthrough with its own camera renders (replacing the file's cameras, animated or not).
TEST_F(CliErrors, WalkthroughWithLookAtCamera) {
  const std::string animated = std::string(IRAD_SOURCE_DIR) + "/data/cornell_animated.gltf";
  const CliRun r = irad("walkthrough " + animated + " -o '" + (dir_ / "f%d.exr").string() +
                        "' --frames 0:2 --paths 4 --size 16x16 --gl osmesa --quiet"
                        " --look-from 0.278,0.273,-0.8 --look-at 0.278,0.273,0 --yfov 50");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "f0.exr"));
  EXPECT_TRUE(fs::exists(dir_ / "f1.exr"));
}

} // namespace
