#pragma once
// The exact-visibility VPL estimator ("rt-vpl"): the very same VPL list and clamp as the raster,
// but visibility V(y, x) from Embree shadow rays instead of a shadow map, and the visible point
// from a primary ray through the pixel centre. Raster and rt-vpl may differ only by shadow-map
// error (and the raster's interpolation of positions). Where the primary ray meets a mirror, the
// surface seen in it is shaded (walk/estimators/mirror_pass.h), as the raster's second pass does.
#include "core/camera/view.h"
#include "core/image/image.h"
#include "core/lights/vpl.h"
#include "core/scene/scene.h"
#include "walk/rays/ray_scene.h"

#include <atomic>
#include <glm/glm.hpp>
#include <vector>

namespace irad {

struct VplTracerOptions {
  float clamp = 0.05f;  // d_min as a fraction of the bounding diagonal (as RasterOptions::clamp)
  unsigned threads = 0; // 0: hardware concurrency
  // When it becomes true (a signal handler), no further pixel is started: those left are 0,
  // alpha included.
  const std::atomic<bool>* cancel = nullptr;
  // Receivers of roughness below it shade only their diffuse lobe from the VPLs a ray can meet
  // (RasterOptions::traced_roughness; walk/estimators/glossy_pass.h adds the specular lobe). 0:
  // none.
  float traced_roughness = 0.0f;
};

Image trace_vpls(const Scene& scene, const RayScene& rays, const View& view, const VplSet& vpls,
                 const VplTracerOptions& options);

// Overwrites `pixels` (Image coordinates) of `image` with rt-vpl's values, alpha kept: the
// raster's edge pixels (raster/raster_renderer.h EdgePixelMode::Listed), where its interleaved
// filter and its shadow maps are least sure (docs/accuracy.md). Pixels that see a
// mirror get its L_e alone, as the raster's (walk/estimators/mirror_pass.h adds what it reflects).
void trace_vpl_pixels(const Scene& scene, const RayScene& rays, const View& view,
                      const VplSet& vpls, const VplTracerOptions& options,
                      const std::vector<glm::ivec2>& pixels, Image& image);

} // namespace irad
