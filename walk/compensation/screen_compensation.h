#pragma once
// The clamp's residual at raster speed: screen-space bias compensation (after Novák, Engelhardt &
// Dachsbacher 2011) with an exact fallback. The residual of walk/compensation/bias_compensation.h,
//   R(x) = rho(x) E_w[(1 - d^2 / d(y)^2)+ L(y -> x)]   (w cosine-distributed, y its hit, d =
//   |x-y|),
// at a glossy x E_w[f cos / pdf (1 - d^2 / d(y)^2)+ L(y -> x)] with w from the BRDF's sampling
// (its diffuse lobe alone where the glossy pass traces the specular one), and a glossy y's image
// value scaled toward x (walk/compensation/screen_lookup.h camera_to),
// needs the radiance leaving the gather hit y. For a diffuse surface that radiance is the same
// toward x as toward the camera, so where the camera sees y the clamped image itself holds it:
// L(y -> x) = image(pixel of y). Only the y the camera does not see (hidden, outside the image,
// or where it sees a mirror) are evaluated exactly: L_e(y) + the clamped VPLs' radiance with
// shadow rays (walk/estimators/vpl_gather.h). Each gather sample costs two short rays instead of a
// shadow ray per VPL. Mirrors: no residual on a mirror pixel, and a gather ray that hits a mirror
// counts 0 (the light a mirror reflects within d(y) is left out).
//
// The recursion of R (the light the clamp removes at y itself) comes from iterating:
//   R_0 = 0,  R_{k+1}(x) = rho(x) E[(1 - d^2/d(y)^2)+ (image + R_k)(y)],
// the same gather samples each time; `iterations` = 1 is Kollig & Keller's first level. A fallback
// sample carries no recursion (its R(y) is left out: the second-order term of a hidden point).
//
// Where the image's pixel and y differ: y's value is that of the pixel its projection falls in
// when that pixel's centre sees y's surface (turned the same way, on y's tangent plane within
// half a pixel), else of the nearest neighbour whose centre does, else y is evaluated exactly.
// Taking whatever the pixel shows puts the other face of a crease (or the surface behind a
// silhouette) in y's place just where the residual is large: a bias all rounds share, rt-vpl's
// 4x4-block relMSE on the Cornell box at 128x128 with 8 rounds 7.8e-5 (32 rounds: 7.4e-5),
// 1.4e-5 with the test (docs/accuracy.md). The image is the estimator's own (interleaved,
// resolved) answer, so the residual inherits its light-set error, not more.
#include "core/camera/view.h"
#include "core/image/image.h"
#include "core/lights/vpl.h"
#include "core/scene/scene.h"
#include "walk/rays/ray_scene.h"

#include <cstdint>

namespace irad {

struct ScreenCompensationOptions {
  float clamp = 0.05f;       // the global d_min as a fraction of the diagonal (as the estimators)
  std::uint32_t samples = 8; // gather directions per pixel
  int iterations = 3;        // levels of the recursion (>= 1)
  std::uint64_t seed = 0;
  unsigned threads = 0; // 0: all cores
  // Whether the exactly evaluated hits add their emission L_e(y): false for a part of the paths
  // that does not hold the emitters (its image holds none either), so that parts add up.
  bool emission = true;
  // Glossy x below this roughness gather for their diffuse lobe alone (the glossy camera pass,
  // walk/estimators/glossy_pass.h, traces their specular lobe unclamped); 0: none.
  float traced_roughness = 0.0f;
};

struct ScreenCompensationStats {
  std::uint64_t gathers = 0;  // gather rays traced
  std::uint64_t in_reach = 0; // of them, hits closer than d(y): the samples with weight > 0
  std::uint64_t fallback = 0; // of those, evaluated exactly (hidden from the camera)
};

// R(x) at the visible point of every pixel centre (alpha 0), for `clamped` (the VPL estimator's
// image of `vpls` in `view`, emitters included).
Image screen_space_residual(const Scene& scene, const RayScene& rays, const View& view,
                            const VplSet& vpls, const Image& clamped,
                            const ScreenCompensationOptions& options,
                            ScreenCompensationStats* stats = nullptr);

} // namespace irad
