#include "core/scene/texture.h"

#include <cmath>

namespace irad {

namespace {

// Reduces a texture coordinate to a bounded range in which the wrap mode gives the same result,
// so that huge coordinates never reach an integer conversion. Non-finite coordinates become 0.
double reduce(float coordinate, Wrap wrap) {
  double t = std::isfinite(coordinate) ? double(coordinate) : 0.0;
  switch (wrap) {
  case Wrap::Repeat:
    return t - std::floor(t); // period 1: [0, 1]
  case Wrap::MirroredRepeat:
    return t - 2.0 * std::floor(0.5 * t); // period 2: [0, 2]
  case Wrap::ClampToEdge:
    break;
  }
  return std::fmin(std::fmax(t, -1.0), 2.0); // beyond [-1, 2] clamping gives the edge texels
}

// Maps an integer texel index to [0, n). Mirrored repeat reflects index space with period 2n,
// which is exactly the texture mirrored about every integer coordinate.
int wrap_index(long i, int n, Wrap wrap) {
  const long size = n;
  switch (wrap) {
  case Wrap::Repeat:
    return int(((i % size) + size) % size);
  case Wrap::MirroredRepeat: {
    const long m = ((i % (2 * size)) + 2 * size) % (2 * size);
    return int(m < size ? m : 2 * size - 1 - m);
  }
  case Wrap::ClampToEdge:
    break;
  }
  return int(i < 0 ? 0 : (i >= size ? size - 1 : i));
}

// Linear-filter footprint along one axis: texel centres lie at (i + 0.5) / n, so the continuous
// texel coordinate is x = t n - 0.5, between texels floor(x) and floor(x) + 1 with weight frac(x).
struct Footprint {
  int i0;
  int i1;
  float w1; // weight of i1; i0 gets 1 - w1
};

Footprint footprint(float coordinate, int n, Wrap wrap) {
  const double x = reduce(coordinate, wrap) * n - 0.5;
  const double f = std::floor(x);
  const long i = long(f);
  return {wrap_index(i, n, wrap), wrap_index(i + 1, n, wrap), float(x - f)};
}

} // namespace

glm::vec4 Texture::sample(glm::vec2 uv) const {
  if (width <= 0 || height <= 0 || texels.size() != std::size_t(width) * std::size_t(height)) {
    return glm::vec4(0.0f);
  }
  const Footprint s = footprint(uv.x, width, wrap_s);
  const Footprint t = footprint(uv.y, height, wrap_t);
  auto texel = [&](int x, int y) { return texels[std::size_t(y) * std::size_t(width) + x]; };
  const glm::vec4 top = glm::mix(texel(s.i0, t.i0), texel(s.i1, t.i0), s.w1);
  const glm::vec4 bottom = glm::mix(texel(s.i0, t.i1), texel(s.i1, t.i1), s.w1);
  return glm::mix(top, bottom, t.w1);
}

glm::vec4 Texture::mean() const {
  if (texels.empty()) return glm::vec4(0.0f);
  glm::dvec4 sum(0.0);
  for (const glm::vec4& t : texels) sum += glm::dvec4(t);
  return glm::vec4(sum / double(texels.size()));
}

// IEC 61966-2-1 EOTF: c / 12.92 below the knee, ((c + 0.055) / 1.055)^2.4 above it.
float srgb_to_linear(float c) {
  if (c <= 0.04045f) return c / 12.92f;
  return float(std::pow((double(c) + 0.055) / 1.055, 2.4));
}

} // namespace irad
