#pragma once
// Picking an entry of a discrete distribution by its inclusive CDF (cdf[n - 1] == 1), reusing the
// uniform number for what follows: the light sampler's choice of a light, the environment's of a
// row and a column.
#include <algorithm>
#include <cmath>
#include <cstddef>

namespace irad {

// The entry k whose step [cdf[k - 1], cdf[k]) holds u in [0, 1) (the last one for u at or above
// the top), skipping zero-width entries at the end, and u rescaled to [0, 1) within that step
// (`rest`; 0.5 for a zero-width step).
inline std::size_t pick_from_cdf(const double* cdf, std::size_t n, double u, double& rest) {
  const double* it = std::upper_bound(cdf, cdf + n, u);
  std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(it - cdf), n - 1);
  while (k > 0 && cdf[k] == cdf[k - 1] && !(u < cdf[k])) --k;
  const double lo = k == 0 ? 0.0 : cdf[k - 1];
  const double width = cdf[k] - lo;
  rest = width > 0.0 ? std::clamp((u - lo) / width, 0.0, std::nextafter(1.0, 0.0)) : 0.5;
  return k;
}

} // namespace irad
