// Fresh storage for big arrays (core/util/freed_memory.h): reserve_huge touches only the pages
// past the elements it keeps, on all cores, so a vector grown by it keeps every element and its
// new elements are what resize makes of them. The command line's heap is advised huge pages.
#include "core/util/freed_memory.h"
#include "tests/test_paths.h"

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

// AddressSanitizer's allocator replaces glibc's heap (the sanitizers' run:
// tests/run_sanitizers.sh).
#if defined(__SANITIZE_ADDRESS__)
#define IRAD_TEST_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define IRAD_TEST_ADDRESS_SANITIZER 1
#endif
#endif

namespace irad {
namespace IRAD_UNITY_ID {

TEST(FreedMemory, ReserveHugeKeepsTheElementsAndTouchesOnlyTheNewStorage) {
  std::vector<std::uint32_t> v(3u << 20); // 12 MiB kept: their pages must not be written
  std::iota(v.begin(), v.end(), 1u);
  reserve_huge(v, 8u << 20); // 32 MiB: 20 MiB of fresh pages touched
  ASSERT_GE(v.capacity(), std::size_t{8} << 20);
  bool kept = true;
  for (std::size_t i = 0; i < v.size(); ++i) kept = kept && v[i] == i + 1;
  EXPECT_TRUE(kept);
  v.resize(8u << 20);
  bool zero = true;
  for (std::size_t i = std::size_t{3} << 20; i < v.size(); ++i) zero = zero && v[i] == 0;
  EXPECT_TRUE(zero);
}

TEST(FreedMemory, TouchPagesWritesOnlyItsRange) {
  std::vector<unsigned char> bytes(std::size_t{12} << 20, 7);
  touch_pages(bytes.data() + 4096, (std::size_t{8} << 20) + 1); // a page's first byte each
  std::size_t written = 0, outside = 0;
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    const bool inside = i >= 4096 && i < 4096 + (std::size_t{8} << 20) + 1;
    if (bytes[i] != 7) (inside ? written : outside) += 1;
  }
  EXPECT_EQ(written, (std::size_t{8} << 20) / 4096 + 1); // 2049 pages begin in the range
  EXPECT_EQ(outside, 0u);
}

// The command line's heap in transparent huge pages (apps/main.cpp runs irad again with glibc's
// tunable glibc.malloc.hugetlb=1): --stats reports what the kernel says of its heap
// (/proc/self/smaps THPeligible): eligible unless the kernel's mode is "never", also where the
// caller gives another tunable; not eligible where the caller turns it off and the mode is
// "madvise" (in "always" every heap is).
TEST(FreedMemory, TheCommandLineAdvisesItsHeapHugePages) {
#if defined(IRAD_TEST_ADDRESS_SANITIZER)
  GTEST_SKIP() << "AddressSanitizer's allocator is not glibc's heap";
#endif
  std::ifstream mode_file("/sys/kernel/mm/transparent_hugepage/enabled");
  std::stringstream mode_text;
  mode_text << mode_file.rdbuf();
  const std::string mode = mode_text.str();
  if (mode.empty()) {
    GTEST_SKIP() << "no transparent huge pages here";
  }
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(::testing::TempDir()) / "irad_huge_heap";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto huge = [&](const std::string& env) {
    const fs::path stats = dir / "stats.json";
    const std::string cmd = env + " " + std::string(IRAD_BINARY) + " render " + IRAD_SOURCE_DIR +
                            "/data/cornell_box.gltf -o " + (dir / "c.png").string() +
                            " --size 16x16 --paths 16 --quiet --stats " + stats.string();
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    std::ifstream in(stats);
    return nlohmann::json::parse(in)["heap_huge_pages"].get<bool>();
  };
  const bool never = mode.find("[never]") != std::string::npos;
  EXPECT_EQ(huge("GLIBC_TUNABLES="), !never) << mode;
  EXPECT_EQ(huge("GLIBC_TUNABLES=glibc.malloc.tcache_count=4"), !never); // appended to another
  if (mode.find("[madvise]") != std::string::npos) {
    EXPECT_FALSE(huge("GLIBC_TUNABLES=glibc.malloc.hugetlb=0"));
  }
  fs::remove_all(dir);
}

} // namespace IRAD_UNITY_ID
} // namespace irad
