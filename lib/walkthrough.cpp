#include "irad/walkthrough.h"

#include "core/animation/animation.h"
#include "core/camera/view.h"
#include "core/util/error.h"
#include "irad/render.h"
#include "walk/estimators/mirror_pass.h"

#include <glm/gtc/matrix_transform.hpp>

namespace irad {

namespace {

// The camera turned about the vertical axis through the bounds' centre.
Camera orbit_camera(const Camera& c, const Bounds& b, float degrees) {
  Camera moved = c;
  const glm::vec3 centre = b.center();
  const glm::mat4 turn = glm::translate(glm::mat4(1.0f), centre) *
                         glm::rotate(glm::mat4(1.0f), glm::radians(degrees), {0, 1, 0}) *
                         glm::translate(glm::mat4(1.0f), -centre);
  moved.camera_to_world = turn * c.camera_to_world;
  return moved;
}

// The occluder planes as irad::render chooses them for a frame of the walkthrough's size (the
// cached mode's pages always carry them: raster/shadow/shadow_cache.h).
ShadowPlanes planes_for(const Scene& scene, const RayScene& rays, const WalkthroughSettings& s) {
  const int resolution = shadow_resolution_for(0, s.width, s.height);
  return choose_shadow_planes(scene, rays, ShadowPlanes::Auto, resolution).planes;
}

RingOptions ring_options(const WalkthroughSettings& s, std::uint32_t n, ShadowPlanes planes) {
  RingOptions o;
  o.paths = n;
  o.width = s.width;
  o.height = s.height;
  o.raster.backend = s.backend;
  o.raster.shadow_lod.planes = planes;
  return o;
}

RasterOptions raster_options(const WalkthroughSettings& s, ShadowPlanes planes) {
  RasterOptions o;
  o.backend = s.backend;
  o.interleave = s.interleave;
  o.shadow_lod.planes = planes;
  return o;
}

} // namespace

WalkMode parse_walk_mode(const std::string& name) {
  if (name == "ring") return WalkMode::Ring;
  if (name == "cached") return WalkMode::Cached;
  if (name == "reshade") return WalkMode::Reshade;
  throw Error("", "--mode", "'" + name + "' is not ring, cached or reshade");
}

const char* walk_mode_name(WalkMode mode) {
  switch (mode) {
  case WalkMode::Ring:
    return "ring";
  case WalkMode::Cached:
    return "cached";
  case WalkMode::Reshade:
    break;
  }
  return "reshade";
}

WalkMode default_walk_mode(const Scene& scene, std::size_t camera, float orbit) {
  const bool animated = scene.animation && camera < scene.animation->camera_node.size() &&
                        scene.animation->camera_node[camera] >= 0;
  return animated || orbit != 0.0f ? WalkMode::Cached : WalkMode::Ring;
}

Walkthrough::Walkthrough(Scene& scene, std::size_t camera, const WalkthroughSettings& settings,
                         Log& log)
    : scene_(scene), camera_(camera), settings_(settings), rays_(scene),
      walk_(scene, rays_, {settings.paths, 64}, log), n_(walk_.header().paths), vpls_(n_),
      lobes_(n_) {
  if (!(settings.fps > 0.0f)) throw Error("", "--fps", "must be positive");
  const ShadowPlanes planes = planes_for(scene, rays_, settings);
  if (settings.mode == WalkMode::Ring)
    ring_ = std::make_unique<RingRenderer>(scene, ring_options(settings, n_, planes));
  else
    raster_ = std::make_unique<RasterRenderer>(scene, raster_options(settings, planes));
}

std::string Walkthrough::description() const {
  return ring_ ? std::string("ring") : raster_->description();
}

void Walkthrough::pose(int frame) {
  if (!scene_.animation || frame == posed_frame_) return;
  scene_.animation->pose(static_cast<float>(frame) / settings_.fps, scene_);
  posed_frame_ = frame;
  if (!scene_.animation->moves_geometry()) return;
  rays_.update(scene_);
  if (ring_) ring_->scene_changed();
  if (raster_) raster_->scene_changed();
}

Camera Walkthrough::camera_at(int frame) {
  pose(frame);
  const float seconds = static_cast<float>(frame) / settings_.fps;
  return orbit_camera(scene_.cameras[camera_], scene_.bounds, settings_.orbit * seconds);
}

void Walkthrough::trace(std::uint32_t slot, const View& view) {
  // Particle i < N of the walk (only those have the design's depth counts n_j): slot i is traced
  // anew with the current geometry; a still scene gives the same VPLs again.
  vpls_[slot].clear();
  lobes_[slot].clear();
  walk_.trace(slot, vpls_[slot], &lobes_[slot]);
  if (ring_) ring_->replace(slot, vpls_[slot], view, lobes_[slot]);
  if (settings_.mode == WalkMode::Cached)
    raster_->cache_path(slot, vpls_[slot], settings_.width, settings_.height, lobes_[slot]);
  ++next_;
}

void Walkthrough::warm_up(int frame) {
  const View view = make_view(camera_at(frame), scene_.bounds, settings_.width, settings_.height);
  while (next_ < n_) trace(next_ % n_, view);
}

Image Walkthrough::frame(int frame) {
  return this->frame(frame, camera_at(frame));
}

Image Walkthrough::frame(int frame, const Camera& camera) {
  pose(frame);
  const View view = make_view(camera, scene_.bounds, settings_.width, settings_.height);
  trace(next_ % n_, view); // one new path per frame, with the current geometry
  const WalkMode mode = settings_.mode;
  // Every path's VPLs, gathered once, for the modes and passes that need them all.
  const VplSet all = mode == WalkMode::Reshade || scene_.has_specular() ? all_vpls() : VplSet{};
  Image image = mode == WalkMode::Ring     ? ring_->frame(view)
                : mode == WalkMode::Cached ? raster_->render_cached(view)
                                           : raster_->render(view, all);
  if (scene_.has_specular()) // visible mirrors: the ray-traced pass (walk/estimators/mirror_pass.h)
    add_mirror_pass(scene_, rays_, view, all, {RasterOptions{}.clamp, 0, nullptr}, image);
  return image;
}

VplSet Walkthrough::all_vpls() const {
  VplSet all = walk_.header();
  for (std::size_t p = 0; p < vpls_.size(); ++p) {
    const auto first = static_cast<std::int32_t>(all.lobes.size());
    for (Vpl v : vpls_[p]) {
      if (v.lobe >= 0) v.lobe += first; // the path's lobes after those of the paths before
      all.vpls.push_back(v);
    }
    all.lobes.insert(all.lobes.end(), lobes_[p].begin(), lobes_[p].end());
  }
  return all;
}

} // namespace irad
