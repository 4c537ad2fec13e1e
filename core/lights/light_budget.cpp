#include "core/lights/light_budget.h"

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

// A representative carries a cluster's light (about 16 VPLs under the light budget), so its
// shadow map's error weighs as much as theirs together. With the lookups trusting the receiver's
// plane and taking the occluder's plane both ways (raster/glsl/cube_glsl.h), the maps' error is
// small against one light set's. Measured against pt references (4x4-block relMSE, time):
// Cornell 256x256, seeds 0-4, R = 64 1.58e-4 in 1.02-1.14 s (median 1.04) against R = 128
// 1.52e-4 in 1.15-1.47 s (median 1.21); 2 rounds (seeds 0-2) 9.1e-5 in 2.0-2.4 s against 8.7e-5
// in 2.35-2.9 s. The maps' error stays while the mean of M rounds divides the light sets' by M:
// at 4 rounds the two are level (5.6e-5 in 4.2-5.2 s against 5.1e-5 in 5.1-5.7 s), and godot
// 128x128 (where the rule gives 64) at 8 rounds is better off with 128 (5.4e-4 in 30 s; R = 64
// needs 8 rounds and 16 s for 7.1e-4, R = 128 4 rounds and 15 s for 6.6e-4). So without tracing,
// from 4 rounds on the faces are at least half the image's side up to 128. Doubling again does
// not pay (Cornell 256x256, 8 rounds: R = 128 2.97e-5 in 10.7 s, R = 256 2.80e-5 in 15.9 s; pt:
// 3.4e-5 and 2.3e-5 at those times).
// With the pixels whose lookups the maps cannot decide traced (trace_edge_pixels below, from 2
// rounds on), the tracing takes over what the finer faces buy, and the rule stands: Cornell
// 256x256, 4 rounds, R = 64 4.62e-5 in 5.8 s against R = 128 4.64e-5 in 7.0 s (4078 unsure
// pixels traced against 2343); 16 rounds 1.35e-5 in 22.6 s against 1.39e-5 in 24.1 s; godot
// 128x128, 4 rounds, R = 64 5.10e-4 in 9.1 s against R = 128 5.02e-4 in 15.9 s.
int representative_shadow_resolution(int rule, int width, int height, unsigned rounds,
                                     bool traced) {
  if (rounds < 4 || traced) return rule;
  return std::max(rule, std::min(128, std::max(width, height) / 2));
}

// The traced pixels: the edge pixels (6.6 % of the Cornell box at 256x256, 12-22 % of godot and
// zdm2 at 128x128) and the unsure ones (raster/image/edge_pixels.h: where the shadow maps cannot
// decide a tenth of a pixel's light; 3.6 % of the Cornell box at 256x256, 4-11 % of godot and
// zdm2 at 128x128), which the shading finds (a tenth more shading without occluder planes,
// nothing with them). Measured against pt references (4x4-block relMSE, time, docs/accuracy.md),
// nothing traced -> both traced: one round, Cornell 1.89e-4 in 1.31 s -> 1.75e-4 in 1.49 s (a
// loss at equal time), godot 1.40e-3 in 2.48 s -> 1.03e-3 in 2.94 s, zdm2 1.65e-3 in 5.7 s ->
// 1.14e-3 in 6.1 s; two rounds, Cornell 1.00e-4 in 2.49 s -> 8.8e-5 in 2.84 s (level), godot
// 1.08e-3 in 4.66 s -> 7.2e-4 in 4.82 s. Nothing traced -> the edge pixels alone (6-15 % more
// per round) -> both: 4 rounds, godot 8.07e-4 -> 7.07e-4 for 5 % more -> 5.10e-4 in the same
// time (rt-vpl 4.73e-4), zdm2 9.83e-4 -> 8.15e-4 in the same time (edge pixels alone); 16 rounds,
// Cornell 2.04e-5 in 18.8 s -> 1.56e-5 in 21.5 s (pt: about 1.9e-5 in that time) -> 1.39e-5 in
// 24.9 s. One round, the quick look, keeps the raster's speed.
bool trace_edge_pixels(unsigned rounds) {
  return rounds >= 2;
}

} // namespace irad
