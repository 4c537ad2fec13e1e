// The same input, options and thread count give a bit-identical EXR on the same machine: every
// estimator is rendered twice through the command line and the files compared byte for byte.
// The path tracer is also the same whatever the thread count (one RNG stream per pixel, sample).
#include "core/util/parallel_rows.h"
#include "tests/test_paths.h"

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <stdexcept>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

namespace IRAD_UNITY_ID {

namespace fs = std::filesystem;

std::vector<char> bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class Determinism : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("irad_determinism_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Renders the Cornell box to NAME.exr with `options`; returns the file's bytes.
  std::vector<char> render(const std::string& name, const std::string& options) {
    const fs::path out = dir_ / (name + ".exr");
    const std::string cmd = std::string(IRAD_BINARY) + " render " + IRAD_SOURCE_DIR +
                            "/data/cornell_box.gltf -o " + out.string() + " --size 48x40 " +
                            options + " --quiet";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    return bytes(out);
  }

  fs::path dir_;
};

TEST_F(Determinism, RasterIsBitIdentical) {
  const std::vector<char> a = render("raster_a", "--paths 64");
  ASSERT_GT(a.size(), 1000u);
  EXPECT_EQ(a, render("raster_b", "--paths 64"));
  const std::string reference = "--paths 64 --interleave 1";
  EXPECT_EQ(render("raster_c", reference), render("raster_d", reference));
}

TEST_F(Determinism, RtVplIsBitIdentical) {
  const std::string options = "--estimator rt-vpl --paths 64 --threads 2";
  const std::vector<char> a = render("rtvpl_a", options);
  ASSERT_GT(a.size(), 1000u);
  EXPECT_EQ(a, render("rtvpl_b", options));
}

TEST_F(Determinism, PathTracerIsBitIdenticalForAnyThreadCount) {
  const std::vector<char> a = render("pt_a", "--estimator pt --spp 4 --seed 7 --threads 2");
  ASSERT_GT(a.size(), 1000u);
  EXPECT_EQ(a, render("pt_b", "--estimator pt --spp 4 --seed 7 --threads 2"));
  EXPECT_EQ(a, render("pt_c", "--estimator pt --spp 4 --seed 7 --threads 1"));
  EXPECT_NE(a, render("pt_d", "--estimator pt --spp 4 --seed 8 --threads 2"));
}

// parallel_tasks (the shadow hierarchy's build): every task once, each worker index below the
// worker count, and a task's exception rethrown on the caller's thread after the others stopped.
TEST(ParallelTasks, RunsEachTaskOnceAndRethrows) {
  const unsigned workers = irad::worker_count(3, 100);
  EXPECT_EQ(workers, 3u); // as many as asked, at most one per task
  EXPECT_EQ(irad::worker_count(3, 2), 2u);
  std::vector<int> runs(100, 0);
  std::atomic<bool> bad_worker{false};
  irad::parallel_tasks(100, 3, [&](int t, unsigned w) {
    ++runs[static_cast<std::size_t>(t)];
    if (w >= workers) bad_worker = true;
  });
  EXPECT_EQ(runs, std::vector<int>(100, 1));
  EXPECT_FALSE(bad_worker);
  EXPECT_THROW(irad::parallel_tasks(100, 3,
                                    [](int t, unsigned) {
                                      if (t == 17) throw std::runtime_error("task 17");
                                    }),
               std::runtime_error);
}

// parallel_chunks (the loader's per-element loops): every element of [0, count) exactly once, in
// chunks that do not overlap, across the chunk size's edges; nothing for an empty range.
TEST(ParallelChunks, VisitsEveryElementOnce) {
  for (std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{65535}, std::size_t{65536},
                            std::size_t{65537}, std::size_t{200001}}) {
    std::vector<int> visits(count, 0);
    std::atomic<std::size_t> calls{0};
    irad::parallel_chunks(count, [&](std::size_t first, std::size_t end) {
      ++calls;
      EXPECT_LT(first, end);
      for (std::size_t k = first; k < end; ++k) ++visits[k];
    });
    EXPECT_EQ(visits, std::vector<int>(count, 1)) << count;
    EXPECT_EQ(calls, (count + 65535) / 65536) << count;
  }
}

} // namespace IRAD_UNITY_ID
