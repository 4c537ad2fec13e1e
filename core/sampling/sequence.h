#pragma once
// The point sets the walk can draw its particles from (design.md section 1 uses Halton):
//   halton:           x_i = (Phi_2(i), Phi_3(i), Phi_5(i), ...)
//   scrambled-halton: the same digits, digit j of each dimension mapped through its own random
//                     permutation of {0..b-1} (seeded; random digit scrambling): still
//                     stratified and low-discrepancy, and every point uniform on [0, 1) up to
//                     2^-32, so each seed's estimate is unbiased and seeds are independent (the
//                     rounds of `--rounds`). One permutation for all digits would leave a
//                     point only b! values (2 in base 2): the rounds' light sets would be
//                     correlated and their mean converge to the mean over those few sets.
//   random:           independent uniform numbers from a hash of (seed, dimension, index)
// Every value lies in [0, 1).
#include "core/sampling/radical_inverse.h"

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
  // scrambled-halton: per dimension D permutations of {0..b-1} back to back, one per digit
  std::vector<std::vector<std::uint32_t>> permutations_;
};

// Radical inverse with digit j (including the leading zeros up to 32 bits' worth of digits)
// mapped through the j-th permutation in perms: sum_{j < D} perms[j b + a_j] b^(-j-1) with
// b^D >= 2^32. perms holds D permutations of {0..b-1}; the result is below 1.
double scrambled_radical_inverse(std::uint32_t base, std::uint32_t i,
                                 const std::vector<std::uint32_t>& perms);

} // namespace irad
