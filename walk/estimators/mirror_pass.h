#pragma once
// Visible mirrors (seed section 5.1.2: "the visible specular objects need a second, ray-traced
// pass"): where the camera sees a mirror, the VPL estimator is evaluated at the diffuse surface
// seen in it, with exact visibility, as rt-vpl does everywhere.
#include "core/camera/view.h"
#include "core/image/image.h"
#include "core/lights/vpl.h"
#include "core/scene/scene.h"
#include "walk/rays/ray_scene.h"

#include <atomic>
#include <glm/glm.hpp>

namespace irad {

// Radiance leaving the mirror point `position` (geometric normal `normal`, either side) toward
// the viewer along `dir` (the direction that arrived there): R times, along the reflected ray
// followed through further mirrors (walk/rays/mirror_walk.h), the emission L_e and the gathered
// VPLs (walk/estimators/vpl_gather.h) of the first diffuse surface. 0 when the ray leaves the
// scene.
glm::vec3 mirror_radiance(const Scene& scene, const RayScene& rays, const VplSet& vpls,
                          std::size_t triangle, const glm::vec3& position, const glm::vec3& dir,
                          float dmin, float eps); // dmin: the global clamp (gather_vpls)

struct MirrorPassOptions {
  float clamp = 0.05f;  // d_min as a fraction of the bounding diagonal (as RasterOptions::clamp)
  unsigned threads = 0; // 0: hardware concurrency
  const std::atomic<bool>* cancel = nullptr;
};

// The raster's second pass: adds mirror_radiance to every pixel whose primary ray (through the
// pixel centre, as the raster samples) hits a mirror first; other pixels are untouched (the
// raster gives mirrors no diffuse light). Nothing to do for a scene without mirrors.
void add_mirror_pass(const Scene& scene, const RayScene& rays, const View& view, const VplSet& vpls,
                     const MirrorPassOptions& options, Image& image);

} // namespace irad
