// Replays tests/fuzz_corpus/ (the minimised corpus of the libFuzzer target, fuzz/run.sh) through
// the loader exactly as the fuzzer runs it (fuzz/fuzz_input.h): every input must load or throw
// irad::Error; anything else (another exception, a crash, a broken invariant) fails. Run under
// the sanitizers too (tests/run_sanitizers.sh). Files named seed-* must load, and regression-*
// inputs (one per loader bug found) must give their error.
#include "fuzz/fuzz_input.h"
#include "tests/test_paths.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <string>
#include <unistd.h>
#include <vector>

namespace IRAD_UNITY_ID {

namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(IRAD_SOURCE_DIR) / "tests" / "fuzz_corpus";

std::vector<fs::path> corpus_files(const std::string& prefix = "") {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(kCorpus)) {
    if (entry.is_regular_file() && entry.path().filename().string().rfind(prefix, 0) == 0)
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::uint8_t> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class FuzzCorpus : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("irad_fuzz_corpus_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    irad::fuzz::prepare_dir(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // load_input() on the file: true when it loaded, false on irad::Error.
  bool load(const fs::path& file) {
    const std::vector<std::uint8_t> bytes = read_bytes(file);
    return irad::fuzz::load_input(dir_, bytes.data(), bytes.size());
  }

  fs::path dir_;
};

TEST_F(FuzzCorpus, EveryInputLoadsOrThrowsIradError) {
  const std::vector<fs::path> files = corpus_files();
  ASSERT_GE(files.size(), 20u) << kCorpus;
  std::size_t loaded = 0;
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.filename().string());
    try {
      loaded += load(file) ? 1 : 0;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not an irad::Error: " << e.what();
    }
  }
  // Both outcomes are exercised.
  EXPECT_GT(loaded, 0u);
  EXPECT_LT(loaded, files.size());
}

TEST_F(FuzzCorpus, SeedsLoad) {
  const std::vector<fs::path> seeds = corpus_files("seed-");
  EXPECT_GE(seeds.size(), 10u);
  for (const fs::path& file : seeds) EXPECT_TRUE(load(file)) << file.filename();
}

TEST_F(FuzzCorpus, RegressionInputsGiveTheirError) {
  struct Case {
    const char* file;
    const char* message; // part of the irad::Error
  };
  const Case cases[] = {
      // 6000 nested arrays (tinygltf, converting extras recursively, overflows its stack).
      {"regression-deep-nesting.gltf", "JSON: nested deeper than the limit of 64 levels"},
      // A GLB buffer of byteLength 0 (tinygltf reads its byte 0 with vector::at: out_of_range).
      // Nothing uses the buffer, so its invalid byteLength is only counted in the warning about
      // unused parts; the file's error is that it has no mesh.
      {"regression-glb-empty-buffer.glb", "no triangles"},
      // A negative byteOffset (tinygltf reads it as absent, i.e. 0).
      {"regression-negative-offset.gltf", "bufferViews[0].byteOffset: value -4 is out of range"},
      // A uri out of the scene's folder (tinygltf follows '..', and looks in the current folder).
      {"regression-uri-escape.gltf", "buffers[0]: uri '../buffer.bin' leaves the scene's folder"},
      // A PNG whose empty first IDAT chunk stb_image copies to a null pointer (UBSan: nonnull).
      // The input's POSITION is of unsigned ints (a fuzzer mutation), which the validator refuses
      // before any image is decoded; its texture 0 has no source ("so0rce"), so the PNG is no
      // texture's. The empty IDAT itself is BadInput's image_empty_idat case.
      {"regression-png-empty-idat.glb",
       "meshes[0].primitives[0].attributes.POSITION: accessor format VEC3/5125 is not allowed"},
  };
  irad::Log log([](const std::string&) {});
  for (const Case& c : cases) {
    SCOPED_TRACE(c.file);
    const fs::path source = kCorpus / c.file;
    ASSERT_TRUE(fs::exists(source));
    const std::vector<std::uint8_t> bytes = read_bytes(source);
    const bool glb = bytes.size() >= 4 && std::equal(bytes.begin(), bytes.begin() + 4, "glTF");
    const fs::path path = dir_ / (glb ? "scene.glb" : "scene.gltf");
    irad::fuzz::write_bytes(path, bytes.data(), bytes.size());
    try {
      irad::load_gltf(path, log, irad::fuzz::fuzz_limits());
      ADD_FAILURE() << "no error";
    } catch (const irad::Error& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
    }
  }
}

} // namespace
