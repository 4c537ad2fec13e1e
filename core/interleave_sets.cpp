#include "core/interleave_sets.h"

#include "core/error.h"
#include "core/rng.h"

#include <numeric>
#include <utility>

namespace irad {

namespace {

// The permutation of block b (a Fisher-Yates shuffle of 0..sets-1 by a stream keyed by b).
std::vector<int> block_permutation(std::uint64_t block, int sets) {
  std::vector<int> p(static_cast<std::size_t>(sets));
  std::iota(p.begin(), p.end(), 0);
  Pcg32 rng(mix64(block), 0x1e7e4ea5u);
  for (int i = sets - 1; i > 0; --i) {
    const auto j = static_cast<int>(rng.next_u32() % static_cast<std::uint32_t>(i + 1));
    std::swap(p[static_cast<std::size_t>(i)], p[static_cast<std::size_t>(j)]);
  }
  return p;
}

} // namespace

InterleaveSets::InterleaveSets(std::uint32_t paths, int sets) : sets_(sets) {
  if (sets < 1) throw Error("", "--interleave", "needs at least one set");
  const auto k2 = static_cast<std::uint32_t>(sets);
  std::vector<std::uint32_t> counts(static_cast<std::size_t>(sets), paths / k2);
  const std::uint32_t rest = paths % k2;
  if (rest > 0) {
    const std::vector<int> last = block_permutation(paths / k2, sets);
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
