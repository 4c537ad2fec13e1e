#pragma once
// Glossy surfaces the VPLs cannot resolve (the seed's second, ray-traced pass, section 5.1.2, for
// narrow lobes as for mirrors): where the camera sees a surface whose roughness lies below
// `roughness`, the VPL estimators shade its diffuse lobe alone from the VPLs a ray can meet
// (RasterOptions::traced_roughness, walk/estimators/vpl_gather.h GlossyView::traced_specular), and
// this pass adds its specular lobe by rays from the camera:
//   L_s(x -> eye) = E[ f_s(wo, wi) (n.wi) / pdf(wi) L(y(wi) -> x) ],
// wi from the specular lobe's visible normals (core/material/brdf.h sample_specular), `samples`
// stratified directions per pixel. A lobe narrower than the VPLs' spacing shows them one by one;
// these rays see the surfaces themselves. L(y -> x), the light y reflects (its emission is the
// light VPLs', which keep the full BRDF: core/lights/vpl.h ray_reachable):
//   - y seen by the camera (walk/compensation/screen_lookup.h): the image's value there less y's
//   L_e (a
//     diffuse surface sends toward x what it sends toward the camera; a glossy one that times
//     the ratio of its directional albedos toward x and toward the camera);
//   - y hidden: the light of 32 VPLs drawn by power at y toward x (an unbiased estimate of
//     walk/estimators/vpl_gather.h gather_vpls, with shadow rays);
//   - y of a narrow lobe itself (its pixel holds its diffuse lobe alone): its diffuse lobe from
//     those 32 VPLs (the lights' own VPLs through its whole BRDF, as at x), and its specular lobe
//     by one ray drawn from it, whose hit is taken by these same rules: glossy-to-glossy light,
//     which 32 points seen through a narrow lobe would miss (a metal sphere in another's
//     reflection goes black) or catch as a spike. After `bounces` such lobes, the 32 VPLs through
//     the whole BRDF;
//   - y on a mirror: the mirror's radiance (walk/estimators/mirror_pass.h); a ray that leaves the
//   scene: the
//     environment.
// The clamp's residual at y is left out (the compensation runs after this pass).
#include "core/camera/view.h"
#include "core/image/image.h"
#include "core/lights/vpl.h"
#include "core/scene/scene.h"
#include "walk/rays/ray_scene.h"

#include <atomic>
#include <cstdint>

namespace irad {

struct GlossyPassOptions {
  float roughness = 0.0f; // receivers below it (walk/estimators/vpl_gather.h narrow_lobe); 0: none
  std::uint32_t samples = 32; // specular directions per pixel
  int bounces = 3;            // narrow lobes met after the camera's that are traced through
  float clamp = 0.05f;        // the exact gathers' global d_min (fraction of the diagonal)
  // Whether escaped rays add the environment: false for a part of the paths that does not hold
  // the direct light (its image holds no background either), so that parts add up.
  bool environment = true;
  std::uint64_t seed = 0;
  unsigned threads = 0; // 0: all cores
  const std::atomic<bool>* cancel = nullptr;
};

struct GlossyPassStats {
  std::uint64_t pixels = 0;    // pixels whose specular lobe was traced
  std::uint64_t rays = 0;      // specular rays traced
  std::uint64_t on_screen = 0; // of them, hits read from the image
  std::uint64_t exact = 0;     // and hits gathered from the VPLs (hidden, or narrow lobes)
};

// Adds L_s to every pixel whose centre sees a surface with a narrow lobe; `image` is the VPL
// estimator's (its diffuse lobe there), read for the hits the camera sees before anything is
// added. Nothing to do when options.roughness is 0 or every material is Lambertian.
void add_glossy_pass(const Scene& scene, const RayScene& rays, const View& view, const VplSet& vpls,
                     const GlossyPassOptions& options, Image& image,
                     GlossyPassStats* stats = nullptr);

} // namespace irad
