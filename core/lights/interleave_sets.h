#pragma once
// Which of the k^2 interleaved sets (raster/image/interleaved.h) a light path's VPLs light, and
// by how much the resolve scales each set. The resolve averages the sets over a k x k window; a
// window cut by geometry (a crease, a silhouette) holds the sets with unequal weights, so each
// set must be an unbiased estimate of 1/k^2 of the light by itself, not only all of them
// together: E[set s] = (n_s / N) L for n_s of the N paths. A hash of the path index gives sets
// of 0.978..1.017 of N/k^2 at N = 16384, k = 2 (0.90..1.08 at N = 4096, k = 4), and since it
// does not change between renders, the creases of the mean of many rounds come out 1-2 % too
// bright (one-sided windows) or too dark (symmetric ones).
//
// Here the paths are taken in blocks of k^2 consecutive indices and each block is dealt out to
// the sets by its own random permutation: every set holds exactly one path of each whole block
// (and the last, partial block's paths go to distinct sets), so the sets are as large as they
// can be, each a stratified sample of the low-discrepancy points (i mod k^2 instead would give a
// set the same leading base-2 digits of Phi_2(i): one strip of the light). scale(s) = N / (k^2
// n_s) makes a set of the partial block's unequal share unbiased too (1 when k^2 divides N).
#include <cstdint>
#include <vector>

namespace irad {

class InterleaveSets {
public:
  // One set: every path in set 0, scale 1.
  InterleaveSets() = default;
  // N paths (indices 0..N-1) dealt to `sets` sets (1..256).
  InterleaveSets(std::uint32_t paths, int sets);

  int sets() const { return sets_; }
  // The set of path i (any i: paths past N continue the blocks).
  int set_of(std::uint32_t path) const;
  // N / (sets n_s) per set (0 for a set no path reaches, N < sets).
  const std::vector<float>& scales() const { return scales_; }

private:
  int sets_ = 1;
  std::vector<float> scales_{1.0f};
};

} // namespace irad
