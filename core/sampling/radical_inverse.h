#pragma once
// Radical inverses and the Halton sequence (design.md section 1).
//   Phi_b(i) = sum_j a_j b^(-j-1)   for i = sum_j a_j b^j.
// The digits are reversed in integer arithmetic and divided once, so for every 32-bit i and
// every base the result is the correctly rounded double of the exact rational, and always < 1.
#include <cstdint>
#include <vector>

namespace irad {

double radical_inverse(std::uint32_t base, std::uint32_t i);

// The first `count` primes: 2, 3, 5, 7, 11, ...
std::vector<std::uint32_t> first_primes(std::size_t count);

// Halton points x_i = (Phi_{b_0}(i), Phi_{b_1}(i), ...) with b_d the d-th prime (0-based).
class Halton {
public:
  explicit Halton(std::size_t dimensions) : bases_(first_primes(dimensions)) {}
  std::size_t dimensions() const { return bases_.size(); }
  std::uint32_t base(std::size_t dimension) const { return bases_[dimension]; }
  double sample(std::size_t dimension, std::uint32_t i) const {
    return radical_inverse(bases_[dimension], i);
  }

private:
  std::vector<std::uint32_t> bases_;
};

} // namespace irad
