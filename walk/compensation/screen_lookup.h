#pragma once
// Where a finished image already holds the radiance leaving a scene point: a diffuse surface point
// y sends the same radiance toward any direction as toward the camera, so where the camera sees y
// the image's value at y's pixel is L(y -> anywhere). The screen-space compensation
// (walk/compensation/screen_compensation.h) and the glossy camera pass
// (walk/estimators/glossy_pass.h) read their gather hits there and evaluate only the hits the
// camera does not see.
#include "core/camera/view.h"
#include "core/scene/scene.h"
#include "walk/estimators/vpl_gather.h"
#include "walk/rays/ray_scene.h"

#include <optional>
#include <vector>

namespace irad {

// What the camera sees at a pixel's centre (visible_point): the point x the pixel's value
// belongs to; nothing for the background and mirrors.
using PixelCentre = std::optional<ShadingPoint>;

// What scales the radiance y sends toward the camera (an image's value) into what it sends toward
// unit `toward`: 1 for a diffuse y; for a glossy one the ratio of its directional albedos toward
// `toward` and toward the camera, per channel (0 where the latter is 0). It carries the Fresnel and
// the lobe's reach, not a highlight's place: the glossy camera pass traces the narrow lobes.
glm::vec3 camera_to(const ShadingPoint& y, const glm::vec3& toward);

class ScreenLookup {
public:
  // Finds every pixel centre's visible point (threads: 0 all cores).
  ScreenLookup(const Scene& scene, const RayScene& rays, const View& view, unsigned threads);

  int width() const { return view_->width; }
  const PixelCentre& centre(int px, int py) const {
    return centres_[static_cast<std::size_t>(py) * static_cast<std::size_t>(view_->width) +
                    static_cast<std::size_t>(px)];
  }

  // The pixel (y * width + x) whose image value is the radiance leaving y toward the camera, or
  // -1 when the camera does not see y's side `n` (outside the image, behind the camera, or
  // hidden). The pixel must see y's surface at its centre (same_surface): y's own pixel, else the
  // nearest of its 8 neighbours that does; a pixel whose centre sees another surface holds that
  // surface's radiance, and at the creases and contacts where the clamp's residual lives that
  // would be a bias the rounds share (docs/accuracy.md). None: -1 (y is evaluated exactly).
  int camera_pixel(const glm::vec3& y, const glm::vec3& n) const;

private:
  // Whether a pixel's centre sees y's surface: a diffuse surface (a mirror's pixel holds another
  // surface's light) turned y's way (cos > 0.95: not the other face of a crease) and on y's
  // tangent plane within half a pixel's footprint at y (not a surface behind or in front).
  static bool same_surface(const PixelCentre& centre, const glm::vec3& y, const glm::vec3& n,
                           float footprint);

  const RayScene* rays_;
  const View* view_;
  float eps_;
  std::vector<PixelCentre> centres_;
};

} // namespace irad
