#pragma once
// One animated property: glTF animation sampler semantics (glTF 2.0 section 3.11), independent
// of the file format. Times are in seconds, finite, >= 0 and strictly increasing. Before the first
// key the property holds the first value, after the last key the last value.
//   STEP:        v_k on [t_k, t_{k+1})
//   LINEAR:      (1 - s) v_k + s v_{k+1},  s = (t - t_k) / (t_{k+1} - t_k); rotations (4
//                components, quaternions x y z w) use slerp along the shorter arc
//   CUBICSPLINE: the cubic Hermite spline through the keys with the file's tangents
//                p(s) = (2s^3 - 3s^2 + 1) v_k + d (s^3 - 2s^2 + s) b_k + (-2s^3 + 3s^2) v_{k+1}
//                       + d (s^3 - s^2) a_{k+1},   d = t_{k+1} - t_k,
//                with a_k the in-tangent and b_k the out-tangent of key k.
// Rotations are normalised after interpolation (a zero result falls back to the nearer key).
#include <glm/glm.hpp>
#include <vector>

namespace irad {

enum class Interpolation { Step, Linear, CubicSpline };

struct Keyframes {
  Interpolation interpolation = Interpolation::Linear;
  bool rotation = false;         // values are unit quaternions (x, y, z, w); else 3-vectors in xyz
  std::vector<float> times;      // one per key
  std::vector<glm::vec4> values; // one per key; CUBICSPLINE: three per key (a_k, v_k, b_k)

  float start() const { return times.front(); }
  float end() const { return times.back(); }
  glm::vec4 sample(float t) const;
};

} // namespace irad
