#include "core/animation/keyframes.h"

#include <algorithm>
#include <glm/gtc/quaternion.hpp>

namespace irad {

namespace {

glm::quat as_quat(const glm::vec4& v) {
  return glm::quat(v.w, v.x, v.y, v.z);
}

glm::vec4 as_vec4(const glm::quat& q) {
  return {q.x, q.y, q.z, q.w};
}

// Unit quaternion of v, or `fallback` when v has (almost) no length.
glm::vec4 normalized_rotation(const glm::vec4& v, const glm::vec4& fallback) {
  const float len = glm::length(v);
  return len > 1e-12f ? v / len : fallback;
}

// Value of key k (the middle element of a CUBICSPLINE triple).
glm::vec4 value(const Keyframes& k, std::size_t i) {
  return k.interpolation == Interpolation::CubicSpline ? k.values[3 * i + 1] : k.values[i];
}

glm::vec4 hermite(const Keyframes& k, std::size_t i, float s, float d) {
  const float s2 = s * s, s3 = s2 * s;
  const glm::vec4 v0 = k.values[3 * i + 1], b0 = k.values[3 * i + 2];
  const glm::vec4 a1 = k.values[3 * (i + 1)], v1 = k.values[3 * (i + 1) + 1];
  return (2 * s3 - 3 * s2 + 1) * v0 + d * (s3 - 2 * s2 + s) * b0 + (-2 * s3 + 3 * s2) * v1 +
         d * (s3 - s2) * a1;
}

} // namespace

glm::vec4 Keyframes::sample(float t) const {
  const std::size_t n = times.size();
  if (!(t > times.front())) return value(*this, 0); // also NaN: the first key
  if (t >= times.back()) return value(*this, n - 1);
  // The key interval [t_i, t_{i+1}) holding t.
  const std::size_t i =
      static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
  const float d = times[i + 1] - times[i];
  const float s = std::clamp((t - times[i]) / d, 0.0f, 1.0f);
  switch (interpolation) {
  case Interpolation::Step:
    return value(*this, i);
  case Interpolation::Linear:
    if (rotation)
      return as_vec4(glm::slerp(as_quat(values[i]), as_quat(values[i + 1]), s)); // shorter arc
    return glm::mix(values[i], values[i + 1], s);
  case Interpolation::CubicSpline:
    break;
  }
  const glm::vec4 p = hermite(*this, i, s, d);
  return rotation ? normalized_rotation(p, value(*this, s < 0.5f ? i : i + 1)) : p;
}

} // namespace irad
