#pragma once
// How many of the N particles of the quasi-random walk reach each reflection (design.md 1):
//   n_j = floor(rho_bar^j N),   D(i) = max{ j : i < n_j },   l_max = max_i D(i),   M = sum_j n_j.
// rho_bar^j N is evaluated in long double and an exact integer floors to itself (rho_bar = 0.5,
// N = 64, j = 6 gives n_6 = 1, not 0). rho_bar >= 1 would never terminate: the depth is capped.
#include <cstdint>
#include <vector>

namespace irad {

class ParticleCounts {
public:
  // depth_cap bounds l_max (it binds only when rho_bar is close to or above 1).
  ParticleCounts(std::uint32_t paths, double rho_bar, int depth_cap);

  std::uint32_t paths() const { return n_.front(); }
  double rho_bar() const { return rho_bar_; }
  int l_max() const { return static_cast<int>(n_.size()) - 1; }
  bool capped() const { return capped_; }
  // n_j for j = 0..l_max (0 beyond).
  std::uint32_t reaching(int j) const { return j <= l_max() ? n_[j] : 0; }
  // D(i): the deepest reflection particle i reaches.
  int depth_of(std::uint32_t i) const;
  // M = sum_j n_j, the number of VPLs the walk leaves (before misses and absorption).
  std::uint64_t vpl_count() const;

private:
  std::vector<std::uint32_t> n_;
  double rho_bar_;
  bool capped_ = false;
};

// floor(x), but x within a relative 1e-9 of an integer floors to that integer.
double robust_floor(long double x);
// The seed's closed form l_max = floor(-log N / log rho_bar) (robust floor); 0 when rho_bar = 0
// or N = 1. Undefined for rho_bar >= 1 (returns -1).
int l_max_closed_form(std::uint32_t paths, double rho_bar);

} // namespace irad
