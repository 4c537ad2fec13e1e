// Radical inverses and the particle counts of the quasi-random walk (design.md section 1).
#include "core/sampling/particle_counts.h"
#include "core/sampling/radical_inverse.h"
#include "core/sampling/sequence.h"
#include "core/util/error.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <limits>

namespace irad {
namespace IRAD_UNITY_ID {

TEST(RadicalInverse, ExactValues) {
  EXPECT_EQ(radical_inverse(2, 0), 0.0);
  EXPECT_EQ(radical_inverse(2, 1), 0.5);
  EXPECT_EQ(radical_inverse(2, 2), 0.25);
  EXPECT_EQ(radical_inverse(2, 3), 0.75);
  EXPECT_EQ(radical_inverse(2, 6), 0.375);
  EXPECT_EQ(radical_inverse(3, 1), 1.0 / 3.0);
  EXPECT_EQ(radical_inverse(3, 2), 2.0 / 3.0);
  EXPECT_EQ(radical_inverse(3, 3), 1.0 / 9.0);
  EXPECT_EQ(radical_inverse(3, 5), 7.0 / 9.0);   // 5 = 12_3 -> 0.21_3 = 2/3 + 1/9
  EXPECT_EQ(radical_inverse(5, 7), 11.0 / 25.0); // 7 = 12_5 -> 0.21_5 = 2/5 + 1/25
  // 2^32 - 1 in base 2 has 32 one-digits: 1 - 2^-32, exactly.
  EXPECT_EQ(radical_inverse(2, 0xffffffffu), 1.0 - std::ldexp(1.0, -32));
}

// Correctly rounded: compare with the digits accumulated in long double from the top.
TEST(RadicalInverse, MatchesLongDoubleReference) {
  for (std::uint32_t base : {2u, 3u, 5u, 7u, 11u, 13u, 97u, 7919u}) {
    for (std::uint32_t i : {1u, 17u, 1000u, 123456789u, 0x80000000u, 0xfffffffeu, 0xffffffffu}) {
      long double value = 0.0L, scale = 1.0L / base;
      for (std::uint32_t n = i; n > 0; n /= base, scale /= base) value += (n % base) * scale;
      EXPECT_NEAR(radical_inverse(base, i), static_cast<double>(value), 1e-16)
          << "base " << base << " i " << i;
    }
  }
}

// The largest values for every digit count are i = b^m - 1 (all digits b - 1), and the largest
// 32-bit index: all must stay below 1.
TEST(RadicalInverse, AlwaysBelowOneForAll32BitIndices) {
  for (std::uint32_t base : first_primes(200)) {
    for (std::uint64_t p = base; p - 1 <= 0xffffffffu; p *= base)
      EXPECT_LT(radical_inverse(base, static_cast<std::uint32_t>(p - 1)), 1.0) << base;
    EXPECT_LT(radical_inverse(base, 0xffffffffu), 1.0);
  }
}

TEST(RadicalInverse, Primes) {
  const std::vector<std::uint32_t> p = first_primes(10);
  EXPECT_EQ(p, (std::vector<std::uint32_t>{2, 3, 5, 7, 11, 13, 17, 19, 23, 29}));
  EXPECT_EQ(first_primes(1000).back(), 7919u);
}

TEST(ParticleCounts, SeedExample) {
  // The seed: rho_bar = 0.5774, N = 64 -> l_max = 7.
  EXPECT_EQ(l_max_closed_form(64, 0.5774), 7);
  EXPECT_EQ(ParticleCounts(64, 0.5774, 64).l_max(), 7);
}

TEST(ParticleCounts, ExactPowersFloorToThemselves) {
  // 0.5^6 * 64 = 1 exactly: n_6 = 1 and l_max = 6.
  const ParticleCounts c(64, 0.5, 64);
  EXPECT_EQ(c.reaching(6), 1u);
  EXPECT_EQ(c.reaching(7), 0u);
  EXPECT_EQ(c.l_max(), 6);
  EXPECT_EQ(l_max_closed_form(64, 0.5), 6);
  // 0.1^3 * 1000 = 1 (0.1 is not exact in binary): still 1.
  EXPECT_EQ(ParticleCounts(1000, 0.1, 64).reaching(3), 1u);
  EXPECT_EQ(l_max_closed_form(1000, 0.1), 3);
  EXPECT_EQ(ParticleCounts(1000, 0.1, 64).l_max(), 3);
}

TEST(ParticleCounts, LmaxEqualsDeepestReflectionOnAGrid) {
  for (std::uint32_t n : {1u, 2u, 3u, 10u, 64u, 100u, 1000u, 1024u, 4096u, 100000u, 1u << 22}) {
    for (double rho : {0.0, 0.01, 0.1, 0.25, 0.3, 0.5, 0.5774, 0.6, 0.75, 0.8, 0.9, 0.95}) {
      const ParticleCounts c(n, rho, 1000);
      int deepest = 0;
      std::uint64_t m = 0;
      for (std::uint32_t i = 0; i < n; i += (n > 5000 ? 97 : 1))
        deepest = std::max(deepest, c.depth_of(i));
      deepest = std::max(deepest, c.depth_of(0)); // particle 0 always goes deepest
      for (int j = 0; j <= c.l_max() + 1; ++j) m += c.reaching(j);
      EXPECT_EQ(c.l_max(), l_max_closed_form(n, rho)) << "N " << n << " rho " << rho;
      EXPECT_EQ(deepest, c.l_max()) << "N " << n << " rho " << rho;
      EXPECT_EQ(m, c.vpl_count());
      EXPECT_LT(static_cast<double>(m), n / (1.0 - rho) + 1e-9);
      EXPECT_FALSE(c.capped());
    }
  }
}

TEST(ParticleCounts, DepthOfMatchesDefinition) {
  const ParticleCounts c(100, 0.6, 64);
  for (std::uint32_t i = 0; i < 100; ++i) {
    int expected = 0;
    while (i < c.reaching(expected + 1)) ++expected;
    EXPECT_EQ(c.depth_of(i), expected) << i;
  }
  // M = sum n_j = 100 + 60 + 36 + 21 + 12 + 7 + 4 + 2 + 1 + 1 (0.6^9 * 100 = 1.0078).
  EXPECT_EQ(c.vpl_count(), 244u);
  EXPECT_EQ(c.l_max(), 9);
}

TEST(ParticleCounts, AlbedoOneIsCapped) {
  const ParticleCounts c(16, 1.0, 20);
  EXPECT_TRUE(c.capped());
  EXPECT_EQ(c.l_max(), 20);
  EXPECT_EQ(c.reaching(20), 16u);
  const ParticleCounts above(16, 1.7, 20);
  EXPECT_TRUE(above.capped());
  EXPECT_EQ(above.reaching(5), 16u); // never more than N particles
}

TEST(ParticleCounts, ZeroAlbedoIsDirectLightOnly) {
  const ParticleCounts c(50, 0.0, 64);
  EXPECT_EQ(c.l_max(), 0);
  EXPECT_EQ(c.vpl_count(), 50u);
}

} // namespace
} // namespace irad

namespace irad {
namespace IRAD_UNITY_ID {

// The first b^k radical inverses fall one into each interval [m b^-k, (m+1) b^-k); a digit
// permutation keeps that (it permutes the intervals).
bool stratified(const Sequence& s, std::size_t dim, std::uint32_t base, int k) {
  std::uint32_t n = 1;
  for (int j = 0; j < k; ++j) n *= base;
  std::vector<int> hits(n, 0);
  for (std::uint32_t i = 0; i < n; ++i) {
    const double v = s.sample(dim, i);
    if (!(v >= 0.0 && v < 1.0)) return false;
    // Halton values are exact multiples of 1/n up to rounding: nudge before flooring.
    ++hits[std::min<std::size_t>(static_cast<std::size_t>(v * n + 1e-9), n - 1)];
  }
  return std::all_of(hits.begin(), hits.end(), [](int h) { return h == 1; });
}

TEST(Sequence, HaltonAndScrambledHaltonAreStratified) {
  const Sequence halton(SequenceKind::Halton, 6);
  const Sequence scrambled(SequenceKind::ScrambledHalton, 6, 42);
  const std::uint32_t bases[] = {2, 3, 5, 7, 11, 13};
  for (std::size_t d = 0; d < 6; ++d) {
    EXPECT_TRUE(stratified(halton, d, bases[d], 3)) << d;
    EXPECT_TRUE(stratified(scrambled, d, bases[d], 3)) << d;
    EXPECT_EQ(halton.sample(d, 5), radical_inverse(bases[d], 5));
  }
  // Scrambling changes the points, and the seed decides how.
  EXPECT_NE(scrambled.sample(0, 1), halton.sample(0, 1));
  EXPECT_EQ(Sequence(SequenceKind::ScrambledHalton, 6, 42).sample(5, 77), scrambled.sample(5, 77));
  EXPECT_NE(Sequence(SequenceKind::ScrambledHalton, 6, 43).sample(5, 77), scrambled.sample(5, 77));
}

// Each digit has its own permutation, so one point over many seeds is uniform on [0, 1): the
// rounds' light sets (`--rounds`, seeds 1..M-1) are independent and each is unbiased. With one
// permutation for every digit, point 7 of the base-2 dimension takes 2 values over all seeds.
TEST(Sequence, ScrambledPointsAreUniformOverSeeds) {
  for (const std::size_t d : {0u, 1u, 4u}) {
    std::vector<double> values;
    double sum = 0.0;
    for (std::uint64_t seed = 1; seed <= 4000; ++seed) {
      values.push_back(Sequence(SequenceKind::ScrambledHalton, 5, seed).sample(d, 7));
      sum += values.back();
    }
    std::sort(values.begin(), values.end());
    const auto distinct = std::unique(values.begin(), values.end()) - values.begin();
    EXPECT_GT(distinct, 3900) << d; // measured 4000 (distinct doubles) in each dimension
    // The mean of 4000 uniforms: standard error 0.0046; bound 4 of them.
    EXPECT_NEAR(sum / 4000.0, 0.5, 0.018) << d;
    // Its quartiles, each within 0.03 (the standard error of a quartile is about 0.007).
    EXPECT_NEAR(values[1000], 0.25, 0.03) << d;
    EXPECT_NEAR(values[3000], 0.75, 0.03) << d;
  }
}

TEST(Sequence, ScrambledValuesStayBelowOne) {
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    const Sequence s(SequenceKind::ScrambledHalton, 30, seed);
    for (std::size_t d = 0; d < 30; ++d)
      for (std::uint32_t i : {0u, 1u, 0xfffffffeu, 0xffffffffu}) EXPECT_LT(s.sample(d, i), 1.0);
  }
}

TEST(Sequence, RandomIsUniformAndSeeded) {
  const Sequence r(SequenceKind::Random, 4, 9);
  double sum = 0.0;
  for (std::uint32_t i = 0; i < 100000; ++i) sum += r.sample(2, i);
  EXPECT_NEAR(sum / 100000.0, 0.5, 0.005); // 5.5 standard errors of a uniform mean
  EXPECT_EQ(Sequence(SequenceKind::Random, 4, 9).sample(3, 12), r.sample(3, 12));
  EXPECT_NE(Sequence(SequenceKind::Random, 4, 10).sample(3, 12), r.sample(3, 12));
  EXPECT_THROW(parse_sequence("sobol"), Error);
}

} // namespace
} // namespace irad
