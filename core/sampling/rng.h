#pragma once
// PCG32 (O'Neill 2014): a small, fast, statistically good generator. Streams are keyed by a
// hash of (seed, pixel, sample) so results never depend on thread scheduling.
#include <cstdint>

namespace irad {

class Pcg32 {
public:
  Pcg32(std::uint64_t seed, std::uint64_t stream) {
    inc_ = (stream << 1u) | 1u;
    next_u32();
    state_ += seed;
    next_u32();
  }
  std::uint32_t next_u32() {
    const std::uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  // Uniform in [0, 1): 32 random bits scaled by 2^-32 (never 1).
  double next_double() { return next_u32() * 0x1p-32; }

private:
  std::uint64_t state_ = 0;
  std::uint64_t inc_ = 1;
};

// SplitMix64 finaliser: decorrelates nearby keys.
inline std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

} // namespace irad
