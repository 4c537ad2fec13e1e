#include "core/sampling/radical_inverse.h"

#include <stdexcept>

namespace irad {

double radical_inverse(std::uint32_t base, std::uint32_t i) {
  if (base < 2) throw std::invalid_argument("radical_inverse: base must be >= 2");
  // reversed = sum_j a_j b^(m-1-j) and scale = b^m, both integers. For i < 2^32 and any base that
  // fits 32 bits, scale <= b * 2^32 < 2^64, so both are exact; reversed < scale.
  std::uint64_t reversed = 0;
  std::uint64_t scale = 1;
  for (std::uint64_t n = i; n > 0; n /= base) {
    reversed = reversed * base + n % base;
    scale *= base;
  }
  // Both operands are exact in double while scale < 2^53 (always true for bases < 2^21); the
  // quotient is then correctly rounded, and reversed <= scale - 1 keeps it below 1.
  const double r = static_cast<double>(reversed) / static_cast<double>(scale);
  return r < 1.0 ? r : 0x1.fffffffffffffp-1;
}

std::vector<std::uint32_t> first_primes(std::size_t count) {
  std::vector<std::uint32_t> primes;
  primes.reserve(count);
  for (std::uint32_t n = 2; primes.size() < count; ++n) {
    bool prime = true;
    for (std::uint32_t p : primes) {
      if (p * p > n) break;
      if (n % p == 0) {
        prime = false;
        break;
      }
    }
    if (prime) primes.push_back(n);
  }
  return primes;
}

} // namespace irad
