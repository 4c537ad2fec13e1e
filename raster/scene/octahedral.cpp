#include "raster/scene/octahedral.h"

#include <cmath>

namespace irad::gl {

namespace {

float sign_not_zero(float x) {
  return x >= 0.0f ? 1.0f : -1.0f;
}

// The octahedron's lower half folded over the diamond's edges, and back (its own inverse).
glm::vec2 fold(const glm::vec2& p) {
  return {(1.0f - std::abs(p.y)) * sign_not_zero(p.x), (1.0f - std::abs(p.x)) * sign_not_zero(p.y)};
}

// The point of [-1, 1]^2 of direction n (not normalized).
glm::vec2 to_square(const glm::vec3& n) {
  const float l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  if (!(l1 > 0.0f)) return {0.0f, 0.0f};
  const glm::vec2 p(n.x / l1, n.y / l1);
  return n.z >= 0.0f ? p : fold(p);
}

} // namespace

glm::vec3 octahedral_decode(glm::i16vec2 e) {
  const glm::vec2 p = glm::max(glm::vec2(e) / kOctahedralScale, glm::vec2(-1.0f));
  glm::vec3 n(p, 1.0f - std::abs(p.x) - std::abs(p.y));
  if (n.z < 0.0f) {
    const glm::vec2 q = fold(p);
    n.x = q.x, n.y = q.y;
  }
  return glm::normalize(n);
}

glm::i16vec2 octahedral_encode(const glm::vec3& n) {
  const glm::vec2 s = glm::round(to_square(n) * kOctahedralScale);
  return {static_cast<std::int16_t>(s.x), static_cast<std::int16_t>(s.y)};
}

} // namespace irad::gl
