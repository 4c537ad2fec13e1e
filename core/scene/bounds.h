#pragma once
// Axis-aligned bounds; every length-like tolerance in irad is a fraction of diagonal().
#include <glm/glm.hpp>
#include <limits>

namespace irad {

struct Bounds {
  glm::vec3 lo{std::numeric_limits<float>::max()};
  glm::vec3 hi{-std::numeric_limits<float>::max()};

  void extend(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  // The union with b (nothing for an empty b: its lo is +max, its hi -max).
  void extend(const Bounds& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool empty() const { return lo.x > hi.x; }
  glm::vec3 center() const { return 0.5f * (lo + hi); }
  float diagonal() const { return empty() ? 0.0f : glm::length(hi - lo); }
};

} // namespace irad
