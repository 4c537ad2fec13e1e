#include "core/sampling/particle_counts.h"

#include <cmath>
#include <stdexcept>

namespace irad {

double robust_floor(long double x) {
  const long double nearest = std::nearbyint(x);
  const long double tolerance = 1e-9L * std::max(1.0L, std::fabs(x));
  return static_cast<double>(std::fabs(x - nearest) <= tolerance ? nearest : std::floor(x));
}

ParticleCounts::ParticleCounts(std::uint32_t paths, double rho_bar, int depth_cap)
    : rho_bar_(rho_bar) {
  if (paths == 0) throw std::invalid_argument("ParticleCounts: need at least one path");
  if (!(rho_bar >= 0.0) || !std::isfinite(rho_bar))
    throw std::invalid_argument("ParticleCounts: rho_bar must be finite and >= 0");
  n_.push_back(paths);
  const long double rho = std::min<long double>(rho_bar, 1.0L);
  long double expected = paths; // rho^j N, one multiplication per step
  for (int j = 1;; ++j) {
    expected *= rho;
    const double nj = robust_floor(expected);
    if (nj < 1.0) break;
    if (j > depth_cap) {
      capped_ = true;
      break;
    }
    n_.push_back(static_cast<std::uint32_t>(nj));
  }
}

int ParticleCounts::depth_of(std::uint32_t i) const {
  // n_j is non-increasing, so D(i) is the last j with i < n_j (binary search over depths).
  int lo = 0, hi = l_max();
  if (i >= n_[0]) return -1;
  while (lo < hi) {
    const int mid = (lo + hi + 1) / 2;
    if (i < n_[mid])
      lo = mid;
    else
      hi = mid - 1;
  }
  return lo;
}

std::uint64_t ParticleCounts::vpl_count() const {
  std::uint64_t m = 0;
  for (std::uint32_t nj : n_) m += nj;
  return m;
}

int l_max_closed_form(std::uint32_t paths, double rho_bar) {
  if (rho_bar >= 1.0) return -1;
  if (rho_bar <= 0.0 || paths <= 1) return 0;
  return static_cast<int>(robust_floor(-std::log(static_cast<long double>(paths)) /
                                       std::log(static_cast<long double>(rho_bar))));
}

} // namespace irad
