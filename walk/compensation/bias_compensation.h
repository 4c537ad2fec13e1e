#pragma once
// What the clamp removes, and its recovery (Kollig & Keller 2004). With the clamped geometry term
// G_c = cos_y cos_x / max(d^2, d_min^2), the VPLs estimate the transport with G_c instead of G; the
// missing part at a point x is
//   R(x) = rho(x)/pi * integral over the hemisphere of cos_x (1 - d^2/d_min^2)+ L(y -> x) dw,
// nonzero only where the surface y seen in direction w is closer than d_min. It is estimated by
// short gather paths: a cosine-distributed direction (f cos / pdf = rho), and at the hit y
//   L(y -> x) = L_e(y) + (clamped VPL radiance at y, exact visibility) + R(y)   (recursively).
// Adding R to a clamped image removes the clamp's bias; punctual lights are never clamped.
#include "core/camera/view.h"
#include "core/image/image.h"
#include "core/lights/vpl.h"
#include "core/scene/scene.h"
#include "walk/rays/ray_scene.h"

#include <cstdint>

namespace irad {

struct BiasCompensationOptions {
  float clamp = 0.05f;        // d_min as a fraction of the bounding diagonal (as the estimators)
  std::uint32_t samples = 16; // gather directions per pixel
  std::uint64_t seed = 0;
  unsigned threads = 0; // 0: all cores
  int max_depth = 16;   // recursion cap; each level is weighted by < rho
};

// R(x) at the visible point of every pixel centre (alpha 1).
Image clamp_residual(const Scene& scene, const RayScene& rays, const View& view, const VplSet& vpls,
                     const BiasCompensationOptions& options);

// The fraction of the VPLs' reflected light that the clamp removes from the image:
// sum R / sum (clamped VPL radiance + R) over the mean of R, G, B (emitters seen directly are not
// counted), estimated on a grid of at most grid x grid pixel centres with exact visibility, its
// rows on `threads` threads (0: all cores; the same result at any count).
double clamped_fraction(const Scene& scene, const RayScene& rays, const View& view,
                        const VplSet& vpls, float clamp, int grid = 64, std::uint32_t samples = 8,
                        unsigned threads = 0);

} // namespace irad
