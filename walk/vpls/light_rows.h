#pragma once
// The reduced light matrix of matrix row-column sampling (core/lights/light_clusters.h): r pixels,
// one drawn in each cell of a grid over the image, and for each the luminance (r + g + b) every VPL
// reflects at its visible point toward the camera, exactly as rt-vpl evaluates it (shadow rays,
// the VPLs' clamp: walk/estimators/vpl_gather.h). Pixels that see the background or a mirror give
// no row.
#include "core/camera/view.h"
#include "core/lights/light_clusters.h"
#include "core/lights/vpl.h"
#include "core/scene/scene.h"
#include "walk/rays/ray_scene.h"

#include <atomic>
#include <cstdint>

namespace irad {

struct LightRowsOptions {
  std::size_t rows = 256; // about this many cells (fewer rows when some see no diffuse surface)
  float clamp = 0.05f;    // the global clamp, for VPLs without their own (core/lights/vpl.h)
  std::uint64_t seed = 0;
  unsigned threads = 0; // 0: all cores
  const std::atomic<bool>* cancel = nullptr;
};

ReducedMatrix light_rows(const Scene& scene, const RayScene& rays, const View& view,
                         const VplSet& vpls, const LightRowsOptions& options);

} // namespace irad
