#include "raster/scene/octahedral.h"

#include <algorithm>
#include <cmath>

namespace irad::gl {

namespace {

float sign_not_zero(float x) {
  return x >= 0.0f ? 1.0f : -1.0f;
}

// The point of [-1, 1]^2 of direction n (not normalized).
glm::vec2 to_square(const glm::vec3& n) {
  const float l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  if (!(l1 > 0.0f)) return {0.0f, 0.0f};
  const glm::vec2 p(n.x / l1, n.y / l1);
  if (n.z >= 0.0f) return p;
  return {(1.0f - std::abs(p.y)) * sign_not_zero(p.x), (1.0f - std::abs(p.x)) * sign_not_zero(p.y)};
}

} // namespace

glm::vec3 octahedral_decode(glm::i16vec2 e) {
  const glm::vec2 p = glm::max(glm::vec2(e) / kOctahedralScale, glm::vec2(-1.0f));
  glm::vec3 n(p, 1.0f - std::abs(p.x) - std::abs(p.y));
  if (n.z < 0.0f) {
    const glm::vec2 folded((1.0f - std::abs(n.y)) * sign_not_zero(n.x),
                           (1.0f - std::abs(n.x)) * sign_not_zero(n.y));
    n.x = folded.x, n.y = folded.y;
  }
  return glm::normalize(n);
}

glm::i16vec2 octahedral_encode(const glm::vec3& n) {
  const glm::vec2 s = to_square(n) * kOctahedralScale;
  const glm::vec2 lo = glm::floor(s);
  // By the distance, not the cosine: the cosines of the four differ below float's resolution.
  glm::i16vec2 best(0, 0);
  float best_distance = 5.0f;
  for (int k = 0; k < 4; ++k) {
    const glm::vec2 c = glm::clamp(lo + glm::vec2(float(k & 1), float(k >> 1)), -kOctahedralScale,
                                   kOctahedralScale);
    const glm::i16vec2 e(static_cast<std::int16_t>(c.x), static_cast<std::int16_t>(c.y));
    const glm::vec3 d = octahedral_decode(e) - n;
    const float distance = glm::dot(d, d);
    if (distance < best_distance) best = e, best_distance = distance;
  }
  return best;
}

} // namespace irad::gl
