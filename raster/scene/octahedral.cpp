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

// The direction of an encoding, not normalized.
glm::vec3 unfold(glm::i16vec2 e) {
  const glm::vec2 p = glm::max(glm::vec2(e) / kOctahedralScale, glm::vec2(-1.0f));
  glm::vec3 n(p, 1.0f - std::abs(p.x) - std::abs(p.y));
  if (n.z < 0.0f) {
    const glm::vec2 folded((1.0f - std::abs(n.y)) * sign_not_zero(n.x),
                           (1.0f - std::abs(n.x)) * sign_not_zero(n.y));
    n.x = folded.x, n.y = folded.y;
  }
  return n;
}

} // namespace

glm::vec3 octahedral_decode(glm::i16vec2 e) {
  return glm::normalize(unfold(e));
}

glm::i16vec2 octahedral_encode(const glm::vec3& n) {
  const glm::vec2 s = glm::round(to_square(n) * kOctahedralScale);
  return {static_cast<std::int16_t>(s.x), static_cast<std::int16_t>(s.y)};
}

} // namespace irad::gl
