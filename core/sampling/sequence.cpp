#include "core/sampling/sequence.h"

#include "core/sampling/rng.h"
#include "core/util/error.h"

#include <numeric>

namespace irad {

SequenceKind parse_sequence(const std::string& name) {
  if (name == "halton") return SequenceKind::Halton;
  if (name == "scrambled-halton") return SequenceKind::ScrambledHalton;
  if (name == "random") return SequenceKind::Random;
  throw Error("", "--sequence",
              "unknown sequence '" + name + "' (halton, scrambled-halton or random)");
}

const char* sequence_name(SequenceKind kind) {
  switch (kind) {
  case SequenceKind::Halton:
    return "halton";
  case SequenceKind::ScrambledHalton:
    return "scrambled-halton";
  case SequenceKind::Random:
    return "random";
  }
  return "?";
}

Sequence::Sequence(SequenceKind kind, std::size_t dimensions, std::uint64_t seed)
    : kind_(kind), seed_(seed), bases_(first_primes(dimensions)) {
  if (kind != SequenceKind::ScrambledHalton) return;
  for (std::size_t d = 0; d < dimensions; ++d) {
    const std::uint32_t b = bases_[d];
    std::vector<std::uint32_t> perms;
    Pcg32 rng(mix64(seed), d); // Fisher-Yates, one stream per dimension, one shuffle per digit
    for (std::uint64_t scale = 1; scale < (1ULL << 32); scale *= b) {
      const std::size_t first = perms.size();
      for (std::uint32_t k = 0; k < b; ++k) perms.push_back(k);
      for (std::uint32_t k = b - 1; k > 0; --k)
        std::swap(perms[first + k], perms[first + rng.next_u32() % (k + 1)]);
    }
    permutations_.push_back(std::move(perms));
  }
}

double Sequence::sample(std::size_t dimension, std::uint32_t i) const {
  switch (kind_) {
  case SequenceKind::Halton:
    return radical_inverse(bases_[dimension], i);
  case SequenceKind::ScrambledHalton:
    return scrambled_radical_inverse(bases_[dimension], i, permutations_[dimension]);
  case SequenceKind::Random: {
    const std::uint64_t key = (static_cast<std::uint64_t>(dimension) << 32) | i;
    return static_cast<double>(mix64(mix64(seed_) ^ key) >> 11) * 0x1p-53;
  }
  }
  return 0.0;
}

double scrambled_radical_inverse(std::uint32_t base, std::uint32_t i,
                                 const std::vector<std::uint32_t>& perms) {
  // D digits cover every 32-bit index; reversed < b^D <= b * 2^32 fits 64 bits for b < 2^21.
  std::uint64_t scale = 1, reversed = 0;
  std::uint64_t n = i;
  for (std::size_t j = 0; scale < (1ULL << 32); ++j) {
    reversed = reversed * base + perms[j * base + n % base];
    n /= base;
    scale *= base;
  }
  const double r = static_cast<double>(reversed) / static_cast<double>(scale);
  return r < 1.0 ? r : 0x1.fffffffffffffp-1;
}

} // namespace irad
