#pragma once
// Maps and lookups the environment tests (test_environment.cpp, test_environment_lighting.cpp)
// share, written from the map's geometry rather than from core/environment/environment.cpp.
#include "core/environment/environment.h"
#include "core/image/image.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <numbers>
#include <random>

namespace irad::env_test {

inline constexpr double kPi = std::numbers::pi;

// Solid angle of a texel of row i in a w x h map, written from the map's geometry (rows are
// bands of equal theta = pi / h, columns wedges of equal phi = 2 pi / w):
// Omega_i = (2 pi / w) (cos theta_top - cos theta_bottom).
inline double texel_solid_angle(int i, int w, int h) {
  return (2.0 * kPi / w) * (std::cos(kPi * i / h) - std::cos(kPi * (i + 1) / h));
}

inline double rec709(const glm::dvec3& c) {
  return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

inline Image black_map(int w, int h) {
  Image map(w, h);
  for (glm::vec4& p : map.pixels()) p = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  return map;
}

// A 2:1 map of random colours in [0.1, 1] per channel, one texel in 20 ten times brighter, one
// in 5 black, and whole black rows (the top one among them).
inline Image random_map(int w, int h, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> value(0.1f, 1.0f), coin(0.0f, 1.0f);
  Image map = black_map(w, h);
  for (int y = 0; y < h; ++y) {
    if (y == 0 || y == h / 3 || y == h - 3) continue;
    for (int x = 0; x < w; ++x) {
      const float gain = coin(rng) < 0.05f ? 10.0f : 1.0f;
      const glm::vec3 c(value(rng), value(rng), value(rng));
      if (coin(rng) >= 0.2f) map.at(x, y) = glm::vec4(gain * c, 1.0f);
    }
  }
  return map;
}

// Column k of the result is column (k + shift) mod w of `map`: the image moved `shift` columns
// to the left, with wrap.
inline Image shift_left(const Image& map, int shift) {
  Image out(map.width(), map.height());
  const int w = map.width();
  for (int y = 0; y < map.height(); ++y)
    for (int x = 0; x < w; ++x) out.at(x, y) = map.at(((x + shift) % w + w) % w, y);
  return out;
}

inline glm::vec3 uniform_direction(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double z = 1.0 - 2.0 * u(rng), phi = 2.0 * kPi * u(rng);
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
          static_cast<float>(z)};
}

// Texel (column, row) of map-frame direction d in a w x h map, and its distance in texels to the
// nearest texel border (small: the lookup may fall either side in float).
struct TexelAt {
  int x = 0, y = 0;
  double border = 0.0;
};
inline TexelAt texel_at(const glm::vec3& d, int w, int h) {
  const glm::vec2 uv = Environment::map_coordinates(d);
  const double fx = double(uv.x) * w, fy = double(uv.y) * h;
  TexelAt t;
  t.x = std::clamp(static_cast<int>(std::floor(fx)), 0, w - 1);
  t.y = std::clamp(static_cast<int>(std::floor(fy)), 0, h - 1);
  t.border = std::min(std::abs(fx - std::round(fx)), std::abs(fy - std::round(fy)));
  return t;
}

// R_y(a) (right-handed about +Y: +Z toward +X), the map-to-world turn of
// core/environment/environment.h.
inline glm::vec3 rotate_y(const glm::vec3& d, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {static_cast<float>(c * d.x + s * d.z), d.y, static_cast<float>(-s * d.x + c * d.z)};
}

} // namespace irad::env_test
