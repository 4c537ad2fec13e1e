// SIGINT and SIGTERM during `irad render`, sent to a real process (fork, exec, kill): the render
// stops, nothing is written (no image, no stats, no .tmp), and the process ends by the signal;
// with --partial the image accumulated so far is written as OUT.partial.EXT. Also: the --stats
// file is written atomically.
#include "core/image/image.h"
#include "core/image/image_io.h"
#include "tests/test_paths.h"

#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace IRAD_UNITY_ID {

namespace fs = std::filesystem;

const std::string kBox = std::string(IRAD_SOURCE_DIR) + "/data/cornell_box.gltf";

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class Interrupt : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("irad_interrupt_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Starts `irad ARGS...` with stdout to /dev/null and stderr to dir/stderr.txt.
  pid_t spawn(const std::vector<std::string>& args) {
    const std::string err = (dir_ / "stderr.txt").string();
    const pid_t pid = ::fork();
    if (pid == 0) {
      const int null = ::open("/dev/null", O_WRONLY);
      const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(null, STDOUT_FILENO);
      ::dup2(e, STDERR_FILENO);
      std::vector<char*> argv;
      argv.push_back(const_cast<char*>(IRAD_BINARY));
      for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      ::execv(IRAD_BINARY, argv.data());
      ::_exit(127);
    }
    return pid;
  }

  // The wait status of `pid`, or -1 (after killing it) when it runs longer than `limit`.
  static int wait_for(pid_t pid, std::chrono::seconds limit) {
    const auto end = std::chrono::steady_clock::now() + limit;
    int status = 0;
    while (::waitpid(pid, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > end) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, &status, 0);
        return -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return status;
  }

  // Runs a render that takes minutes, sends `signal` after `delay`, and returns the wait status.
  int interrupt(std::vector<std::string> args, int signal, std::chrono::milliseconds delay) {
    const pid_t pid = spawn(args);
    std::this_thread::sleep_for(delay);
    EXPECT_EQ(::waitpid(pid, nullptr, WNOHANG), 0) << "the render ended before the signal";
    ::kill(pid, signal);
    return wait_for(pid, std::chrono::seconds(60));
  }

  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }

  std::string out(const char* name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

// A path-traced render of minutes: 20000 samples per pixel.
std::vector<std::string> long_pt(const std::string& exr, const std::string& png,
                                 const std::string& stats) {
  return {"render",      kBox, "-o",    exr,     "-o",     png,     "--stats",   stats,
          "--estimator", "pt", "--spp", "20000", "--size", "64x64", "--threads", "2"};
}

TEST_F(Interrupt, SigintDuringThePathTracerWritesNothing) {
  const int status = interrupt(long_pt(out("a.exr"), out("a.png"), out("a.json")), SIGINT,
                               std::chrono::milliseconds(1500));
  ASSERT_TRUE(WIFSIGNALED(status)) << status;
  EXPECT_EQ(WTERMSIG(status), SIGINT);
  EXPECT_EQ(files(), std::vector<std::string>{"stderr.txt"});
  const std::string err = read_text(dir_ / "stderr.txt");
  EXPECT_NE(err.find("interrupted by SIGINT; nothing written"), std::string::npos) << err;
}

TEST_F(Interrupt, SigtermDuringTheRasterWritesNothing) {
  // 200000 paths: about 400000 VPL passes.
  const int status = interrupt({"render", kBox, "-o", out("r.exr"), "--paths", "200000", "--size",
                                "64x64", "--stats", out("r.json")},
                               SIGTERM, std::chrono::milliseconds(2500));
  ASSERT_TRUE(WIFSIGNALED(status)) << status;
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_EQ(files(), std::vector<std::string>{"stderr.txt"});
  const std::string err = read_text(dir_ / "stderr.txt");
  EXPECT_NE(err.find("interrupted by SIGTERM; nothing written"), std::string::npos) << err;
}

TEST_F(Interrupt, PartialWritesWhatWasAccumulatedUnderItsOwnName) {
  std::vector<std::string> args = long_pt(out("p.exr"), out("p.png"), out("p.json"));
  args.push_back("--partial");
  const int status = interrupt(args, SIGINT, std::chrono::milliseconds(1500));
  ASSERT_TRUE(WIFSIGNALED(status)) << status;
  EXPECT_EQ(WTERMSIG(status), SIGINT);
  EXPECT_EQ(files(), (std::vector<std::string>{"p.partial.exr", "p.partial.png", "stderr.txt"}));
  const std::string err = read_text(dir_ / "stderr.txt");
  EXPECT_NE(err.find("partial image in " + out("p.partial.exr") + ", " + out("p.partial.png")),
            std::string::npos)
      << err;
  // Pixels done have alpha 1, the others are all 0.
  const irad::Image image = irad::read_exr(dir_ / "p.partial.exr");
  ASSERT_EQ(image.width(), 64);
  std::size_t done = 0, left = 0;
  for (const glm::vec4& p : image.pixels()) {
    if (p.a == 1.0f) ++done;
    if (p == glm::vec4(0.0f)) ++left;
  }
  EXPECT_GT(done, 0u);
  EXPECT_GT(left, 0u);
  EXPECT_EQ(done + left, image.pixels().size());
}

TEST_F(Interrupt, PartialOfTheRtVplEstimator) {
  const int status =
      interrupt({"render", kBox, "-o", out("v.exr"), "--estimator", "rt-vpl", "--paths", "20000",
                 "--clusters", "0", "--size", "64x64", "--threads", "2", "--partial"},
                SIGINT, std::chrono::milliseconds(2000));
  ASSERT_TRUE(WIFSIGNALED(status)) << status;
  EXPECT_EQ(files(), (std::vector<std::string>{"stderr.txt", "v.partial.exr"}));
}

TEST_F(Interrupt, StatsAreWrittenWholeOrNotAtAll) {
  // A folder in the way is refused before the render starts: no image either.
  fs::create_directories(dir_ / "s.json");
  const pid_t pid = spawn({"render", kBox, "-o", out("s.exr"), "--stats", out("s.json"),
                           "--estimator", "pt", "--spp", "1", "--size", "8x8"});
  const int status = wait_for(pid, std::chrono::seconds(60));
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_EQ(read_text(dir_ / "stderr.txt"),
            "irad: error: " + out("s.json") + ": --stats: it exists and is not a regular file\n");
  EXPECT_EQ(files(), (std::vector<std::string>{"s.json", "stderr.txt"}));
  // Written: complete JSON and no .tmp beside it.
  const pid_t ok = spawn({"render", kBox, "-o", out("t.exr"), "--stats", out("t.json"),
                          "--estimator", "pt", "--spp", "1", "--size", "8x8", "--quiet"});
  const int ok_status = wait_for(ok, std::chrono::seconds(60));
  ASSERT_TRUE(WIFEXITED(ok_status));
  EXPECT_EQ(WEXITSTATUS(ok_status), 0);
  EXPECT_EQ(files(), (std::vector<std::string>{"s.json", "stderr.txt", "t.exr", "t.json"}));
  const std::string json = read_text(dir_ / "t.json");
  EXPECT_EQ(json.rfind("{", 0), 0u) << json;
  EXPECT_EQ(json.substr(json.size() - 2), "}\n") << json;
}

} // namespace
