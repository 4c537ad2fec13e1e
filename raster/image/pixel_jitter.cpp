#include "raster/image/pixel_jitter.h"

#include "core/sampling/radical_inverse.h"

#include <algorithm>
#include <cmath>

namespace irad {

glm::vec2 path_jitter_point(std::uint32_t path) {
  // 1/g and 1/g^2 for the plastic number g; the products in double keep every 32-bit index exact
  // to ~1e-7 of a pixel.
  constexpr double a1 = 0.75487766624669276005, a2 = 0.56984029099805326591;
  const double i = static_cast<double>(path);
  const double x = 0.5 + a1 * i, y = 0.5 + a2 * i;
  return {static_cast<float>(x - std::floor(x)), static_cast<float>(y - std::floor(y))};
}

float jitter_amplitude(int depth) {
  // 2^-j. The seed (section 5.1.1) lets the jitter shrink with the path's depth; measured on the
  // Cornell box (64 x 64, N = 64, k = 1, docs/ext/jitter_textures.md), relMSE against the 16x
  // supersampled raster:           edges      interior
  //   no jitter                    0.0235     0.00003
  //   1 at every depth             0.0063     0.00020
  //   1/sqrt(j+1)                  0.0053     0.00007
  //   1/(j+1)                      0.0051     0.00004
  //   2^-j                         0.0050     0.00004
  //   1 at depth 0, 0 beyond       0.0054     0.00003
  // Every VPL casts hard shadows; a deep reflection has few VPLs (n_j = rho_bar^j N), so its
  // shadow edges, sampled at few sub-pixel positions, add more noise than their filtering
  // removes. Direct light (many VPLs, most of the light at an edge) keeps the full footprint.
  return std::ldexp(1.0f, -depth);
}

glm::vec2 vpl_jitter(const Vpl& vpl) {
  return jitter_amplitude(vpl.depth) * (path_jitter_point(vpl.path) - glm::vec2(0.5f));
}

int jitter_stratum(const Vpl& vpl) {
  // Reflection 2 and deeper (amplitude <= 1/4, inside the middle cells' quarter) at the centre:
  // rounded to the middle cells' +-1/8 instead, the interior of the Cornell box of
  // tests/test_jitter.cpp has 1.9x the RMSE (k = 1; docs/ext/jitter_textures.md).
  if (vpl.depth >= 2) return kJitterStrata;
  const glm::vec2 o = vpl_jitter(vpl);
  const auto cell = [](float x) {
    return std::clamp(static_cast<int>(std::floor((x + 0.5f) * kJitterGrid)), 0, kJitterGrid - 1);
  };
  return cell(o.x) + kJitterGrid * cell(o.y);
}

glm::vec2 stratum_offset(int stratum) {
  const glm::vec2 cell(static_cast<float>(stratum % kJitterGrid),
                       static_cast<float>(stratum / kJitterGrid));
  return (cell + 0.5f) / static_cast<float>(kJitterGrid) - 0.5f;
}

glm::vec2 camera_jitter(int s, int count) {
  const float u = (static_cast<float>(s) + 0.5f) / static_cast<float>(count);
  const float v = static_cast<float>(radical_inverse(2, static_cast<std::uint32_t>(s)));
  return glm::vec2(u, v) - glm::vec2(0.5f);
}

glm::mat4 jittered_projection(const glm::mat4& projection, glm::vec2 offset, int width,
                              int height) {
  glm::mat4 shift(1.0f);
  shift[3][0] = -2.0f * offset.x / static_cast<float>(width);
  shift[3][1] = 2.0f * offset.y / static_cast<float>(height);
  return shift * projection;
}

} // namespace irad
