#pragma once
// The point sets the walk can draw its particles from (design.md section 1 uses Halton):
//   halton:           x_i = (Phi_2(i), Phi_3(i), Phi_5(i), ...)
//   scrambled-halton: the same digits, each dimension's digits mapped through one random
//                     permutation of {0..b-1} (seeded): still low-discrepancy, no regular
//                     patterns, an unbiased-in-expectation randomisation
//   random:           independent uniform numbers from a hash of (seed, dimension, index)
// Every value lies in [0, 1).
#include "core/radical_inverse.h"

#include <cstdint>
#include <string>
#include <vector>

namespace irad {

enum class SequenceKind { Halton, ScrambledHalton, Random };

// "halton", "scrambled-halton", "random"; throws irad::Error naming the option otherwise.
SequenceKind parse_sequence(const std::string& name);
const char* sequence_name(SequenceKind kind);

class Sequence {
public:
  Sequence(SequenceKind kind, std::size_t dimensions, std::uint64_t seed = 0);
  SequenceKind kind() const { return kind_; }
  std::size_t dimensions() const { return bases_.size(); }
  double sample(std::size_t dimension, std::uint32_t i) const;

private:
  SequenceKind kind_;
  std::uint64_t seed_;
  std::vector<std::uint32_t> bases_;
  std::vector<std::vector<std::uint32_t>> permutations_; // scrambled-halton: one per dimension
};

// Radical inverse with every digit (including the leading zeros up to 32 bits' worth of digits)
// mapped through perm: sum_{j < D} perm[a_j] b^(-j-1) with b^D >= 2^32. perm must be a
// permutation of {0..b-1}; the result is below 1.
double scrambled_radical_inverse(std::uint32_t base, std::uint32_t i,
                                 const std::vector<std::uint32_t>& perm);

} // namespace irad
