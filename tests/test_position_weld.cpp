// weld_positions (core/mesh/position_weld.h) against meshoptimizer's vertex remap, which the
// hierarchy's build welded with before: the first vertex of each of meshoptimizer's classes.
#include "core/mesh/position_weld.h"

#include <cstring>
#include <gtest/gtest.h>
#include <limits>
#include <meshoptimizer.h>
#include <random>

namespace IRAD_UNITY_ID {

using irad::weld_positions;

// The reference: meshoptimizer's classes (bitwise equal positions), each vertex to its class's
// first vertex.
std::vector<std::uint32_t> meshopt_weld(const std::vector<glm::vec3>& positions) {
  // (meshoptimizer takes a multiple of 3: the positions padded with distinct NaN payloads.)
  std::vector<glm::vec3> padded = positions;
  for (std::uint32_t k = 0; padded.size() % 3 != 0; ++k) {
    std::uint32_t bits = 0x7fc12340u + k;
    float nan = 0.0f;
    std::memcpy(&nan, &bits, sizeof nan);
    padded.emplace_back(nan, 1234.5f, -7.0f);
  }
  std::vector<unsigned int> remap(padded.size());
  const std::size_t unique = meshopt_generateVertexRemap(
      remap.data(), nullptr, padded.size(), padded.data(), padded.size(), sizeof(glm::vec3));
  std::vector<std::uint32_t> first(unique, ~0u), welded(positions.size());
  for (std::uint32_t v = 0; v < positions.size(); ++v) {
    if (first[remap[v]] == ~0u) first[remap[v]] = v;
    welded[v] = first[remap[v]];
  }
  return welded;
}

// n positions drawn from `distinct` values (many repeats), with signed zeros and NaNs.
std::vector<glm::vec3> repeated_positions(std::size_t n, std::size_t distinct, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<glm::vec3> pool(distinct);
  for (glm::vec3& p : pool) p = {u(rng), u(rng), u(rng)};
  pool[0] = {0.0f, 0.0f, 0.0f};
  pool[1] = {-0.0f, 0.0f, 0.0f}; // other bits: not welded to pool[0]
  pool[2] = {std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f};
  pool[3] = {1.0f, 1.0f, 1.0f};
  pool[4] = {1.0f, 1.0f, std::nextafter(1.0f, 2.0f)};
  std::vector<glm::vec3> positions(n);
  std::uniform_int_distribution<std::size_t> pick(0, distinct - 1);
  for (glm::vec3& p : positions) p = pool[pick(rng)];
  return positions;
}

TEST(PositionWeld, GivesMeshoptimizersFirstVertexOfEachPosition) {
  for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{7}, std::size_t{5000}}) {
    const std::vector<glm::vec3> positions =
        repeated_positions(n, std::max<std::size_t>(n / 3, 5), 7);
    EXPECT_EQ(weld_positions(positions, 1), meshopt_weld(positions)) << n << " positions";
  }
}

TEST(PositionWeld, TheSameOnAnyNumberOfThreads) {
  // Over 2^20 positions: parts on more than one thread.
  const std::vector<glm::vec3> positions =
      repeated_positions((std::size_t{1} << 21) + 5, 700000, 3);
  const std::vector<std::uint32_t> reference = meshopt_weld(positions);
  for (const unsigned threads : {1u, 2u, 3u, 8u})
    EXPECT_EQ(weld_positions(positions, threads), reference) << threads << " threads";
}

TEST(PositionWeld, SignedZerosAndNansKeepTheirBits) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<glm::vec3> positions = {{0.0f, 1.0f, 2.0f}, {-0.0f, 1.0f, 2.0f},
                                            {nan, 0.0f, 0.0f},  {0.0f, 1.0f, 2.0f},
                                            {nan, 0.0f, 0.0f},  {-0.0f, 1.0f, 2.0f}};
  EXPECT_EQ(weld_positions(positions), (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 1}));
}

} // namespace IRAD_UNITY_ID
