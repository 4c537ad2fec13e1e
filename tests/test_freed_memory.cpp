// Fresh storage for big arrays (core/util/freed_memory.h): reserve_huge touches only the pages
// past the elements it keeps, on all cores, so a vector grown by it keeps every element and its
// new elements are what resize makes of them.
#include "core/util/freed_memory.h"

#include <cstdint>
#include <gtest/gtest.h>
#include <numeric>
#include <vector>

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

} // namespace IRAD_UNITY_ID
} // namespace irad
