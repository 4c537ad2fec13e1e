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
  bool empty() const { return lo.x > hi.x; }
  glm::vec3 center() const { return 0.5f * (lo + hi); }
  float diagonal() const { return empty() ? 0.0f : glm::length(hi - lo); }
};

} // namespace irad
