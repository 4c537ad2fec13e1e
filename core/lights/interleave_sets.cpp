#include "core/lights/interleave_sets.h"

#include "core/sampling/rng.h"
#include "core/util/error.h"

#include <array>
#include <numeric>
#include <string>
#include <utility>

namespace irad {

namespace {

// At most k^2 sets for k <= 16 (RasterOptions::interleave).
constexpr int kMaxSets = 256;
using Permutation = std::array<std::uint8_t, kMaxSets>;

// The permutation of block b's `sets` positions (a Fisher-Yates shuffle by a stream keyed by b).
Permutation block_permutation(std::uint64_t block, int sets) {
  Permutation p{};
  std::iota(p.begin(), p.begin() + sets, std::uint8_t{0});
  Pcg32 rng(mix64(block), 0x1e7e4ea5u);
  for (int i = sets - 1; i > 0; --i) {
    const auto j = rng.next_u32() % static_cast<std::uint32_t>(i + 1);
    std::swap(p[static_cast<std::size_t>(i)], p[j]);
  }
  return p;
}

} // namespace

InterleaveSets::InterleaveSets(std::uint32_t paths, int sets) : sets_(sets) {
  if (sets < 1 || sets > kMaxSets)
    throw Error("", "--interleave", "needs between 1 and " + std::to_string(kMaxSets) + " sets");
  const auto k2 = static_cast<std::uint32_t>(sets);
  std::vector<std::uint32_t> counts(static_cast<std::size_t>(sets), paths / k2);
  const std::uint32_t rest = paths % k2;
  if (rest > 0) {
    const Permutation last = block_permutation(paths / k2, sets);
    for (std::uint32_t r = 0; r < rest; ++r) ++counts[static_cast<std::size_t>(last[r])];
  }
  scales_.assign(static_cast<std::size_t>(sets), 0.0f);
  for (std::size_t s = 0; s < counts.size(); ++s)
    if (counts[s] > 0)
      scales_[s] =
          static_cast<float>(static_cast<double>(paths) / (static_cast<double>(sets) * counts[s]));
}

int InterleaveSets::set_of(std::uint32_t path) const {
  if (sets_ == 1) return 0;
  const auto k2 = static_cast<std::uint32_t>(sets_);
  return block_permutation(path / k2, sets_)[path % k2];
}

} // namespace irad
