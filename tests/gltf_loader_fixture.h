#pragma once
// The fixture of the glTF loader tests (test_gltf_loader.cpp, test_gltf_loader_errors.cpp): a
// temporary folder per test, a logger that keeps the warnings, and expect_error().
#include "core/gltf/loader.h"
#include "core/scene/scene.h"
#include "core/util/error.h"
#include "core/util/log.h"
#include "tests/gltf_test_scene.h"

#include <filesystem>
#include <gtest/gtest.h>
#include <string>
#include <unistd.h>
#include <vector>

namespace gltf_test {

using irad::Scene;

class GltfLoader : public ::testing::Test {
protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = fs::temp_directory_path() /
          ("irad_gltf_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  Scene load(const fs::path& path) { return irad::load_gltf(path, log); }

  // Loads `path` expecting irad::Error; its message must be one line naming the file and
  // containing `element` and `message`.
  void expect_error(const fs::path& path, const std::string& element, const std::string& message) {
    try {
      load(path);
      ADD_FAILURE() << path << ": no error";
    } catch (const irad::Error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      EXPECT_NE(what.find(path.filename().string()), std::string::npos) << what;
      EXPECT_NE(what.find(element), std::string::npos) << what;
      EXPECT_NE(what.find(message), std::string::npos) << what;
    }
  }

  int warnings_containing(const std::string& text) const {
    int n = 0;
    for (const std::string& w : warnings) n += w.find(text) != std::string::npos ? 1 : 0;
    return n;
  }

  fs::path dir;
  std::vector<std::string> warnings;
  irad::Log log{[this](const std::string& line) { warnings.push_back(line); }};
};

} // namespace gltf_test
