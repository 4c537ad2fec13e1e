#include "core/light_budget.h"

#include <algorithm>

namespace irad {

std::uint32_t budget_paths(std::size_t pilot_vpls, const LightBudget& budget) {
  const std::uint32_t lo = std::max<std::uint32_t>(budget.min_paths, 1);
  const std::uint32_t hi = std::max(budget.max_paths, lo);
  if (pilot_vpls == 0 || budget.pilot_paths == 0) return lo; // no VPLs: N does not matter
  // The largest power of two N with N * pilot_vpls <= vpls * pilot_paths (exact in integers).
  const auto fits = [&](std::uint64_t n) {
    return n * pilot_vpls <= std::uint64_t(budget.vpls) * budget.pilot_paths;
  };
  std::uint64_t n = 1;
  while (n * 2 <= hi && fits(n * 2)) n *= 2;
  return std::clamp(static_cast<std::uint32_t>(n), lo, hi);
}

std::size_t budget_clusters(std::size_t vpls, const LightBudget& budget) {
  const std::size_t per = std::max<std::size_t>(budget.vpls_per_cluster, 1);
  if (vpls <= budget.min_clusters * per) return 0;
  return std::clamp(vpls / per, budget.min_clusters,
                    std::max(budget.max_clusters, budget.min_clusters));
}

} // namespace irad
