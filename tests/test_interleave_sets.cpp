// core/lights/interleave_sets.h: the paths dealt to the interleaved sets in blocks.
#include "core/lights/interleave_sets.h"

#include <gtest/gtest.h>

#include <set>
#include <vector>

namespace irad {
namespace IRAD_UNITY_ID {

std::vector<int> counts(const InterleaveSets& s, std::uint32_t paths) {
  std::vector<int> n(static_cast<std::size_t>(s.sets()), 0);
  for (std::uint32_t i = 0; i < paths; ++i) ++n.at(static_cast<std::size_t>(s.set_of(i)));
  return n;
}

// Every block of k^2 consecutive paths holds each set once: the sets are equal when k^2 divides
// N, and their scales are 1.
TEST(InterleaveSets, EveryBlockDealsOnePathToEachSet) {
  for (const int sets : {4, 9, 16, 64}) {
    const std::uint32_t paths = 256u * static_cast<std::uint32_t>(sets);
    const InterleaveSets s(paths, sets);
    for (std::uint32_t b = 0; b < paths; b += static_cast<std::uint32_t>(sets)) {
      std::set<int> seen;
      for (std::uint32_t i = b; i < b + static_cast<std::uint32_t>(sets); ++i)
        seen.insert(s.set_of(i));
      ASSERT_EQ(seen.size(), static_cast<std::size_t>(sets)) << "block at " << b;
    }
    for (const int n : counts(s, paths)) EXPECT_EQ(n, 256);
    for (const float scale : s.scales()) EXPECT_EQ(scale, 1.0f);
  }
}

// A partial last block: sets of n_s paths are scaled by N / (k^2 n_s), so that every set's
// expected share of the light is 1 / k^2; the scaled counts sum to N.
TEST(InterleaveSets, UnequalSetsAreScaledToEqualShares) {
  const std::uint32_t paths = 1000;
  const InterleaveSets s(paths, 16); // 62 whole blocks and 8 paths
  const std::vector<int> n = counts(s, paths);
  int larger = 0;
  double scaled = 0.0;
  for (std::size_t k = 0; k < n.size(); ++k) {
    EXPECT_TRUE(n[k] == 62 || n[k] == 63) << n[k];
    larger += n[k] == 63;
    EXPECT_NEAR(s.scales()[k] * static_cast<float>(n[k]), 1000.0 / 16.0, 1e-4);
    scaled += s.scales()[k] * static_cast<double>(n[k]);
  }
  EXPECT_EQ(larger, 8);
  EXPECT_NEAR(scaled, 1000.0, 1e-3);
  // Fewer paths than sets: the empty sets get no weight.
  const InterleaveSets few(3, 4);
  int empty = 0;
  for (const float scale : few.scales()) empty += scale == 0.0f;
  EXPECT_EQ(empty, 1);
}

// The deal is not i mod k^2 (which would give each set the same leading base-2 digits of the
// Halton points: one strip of the light) and not the same in every block: each set's position
// within the blocks is spread over all k^2 positions, evenly.
TEST(InterleaveSets, PositionsWithinTheBlocksAreSpread) {
  const int sets = 4;
  const std::uint32_t blocks = 4096;
  const InterleaveSets s(blocks * sets, sets);
  std::vector<std::vector<int>> at(sets, std::vector<int>(sets, 0)); // set x position
  for (std::uint32_t b = 0; b < blocks; ++b)
    for (int r = 0; r < sets; ++r) ++at[s.set_of(b * sets + r)][r];
  // Each of the 16 cells expects 1024; binomial sd ~28: 6 sd.
  for (const auto& row : at)
    for (const int n : row) EXPECT_NEAR(n, 1024, 170);
  // One set: everything in set 0.
  const InterleaveSets one(100, 1);
  EXPECT_EQ(one.set_of(57), 0);
  EXPECT_EQ(one.scales(), std::vector<float>{1.0f});
}

} // namespace
} // namespace irad
