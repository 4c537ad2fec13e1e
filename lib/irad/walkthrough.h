#pragma once
// The walkthrough's frame loop (seed section 5.1.3): each frame poses the scene's animation at
// t = frame / fps, refits what moved, traces one new light path with the current geometry and
// replaces the oldest of the N paths, then renders the frame in one of three modes:
//   ring     each path's image is drawn once, from the camera of its frame; the frame is the sum
//            of the N path images (cheapest; a moving camera sees ghosts of old viewpoints).
//   cached   each path's VPLs keep their shadow maps (they do not depend on the camera); every
//            frame re-shades all N paths from the current camera (no ghosts).
//   reshade  every frame redraws every VPL's shadow map and shading pass (the reference: all N
//            paths see the current geometry).
// With moving geometry, ring and cached keep each path's light as it was when the path was
// traced: the lighting lags the motion by up to N frames.
#include "core/scene/scene.h"
#include "core/util/log.h"
#include "raster/context/gl_backend.h"
#include "raster/raster_renderer.h"
#include "raster/ring_renderer.h"
#include "walk/rays/ray_scene.h"
#include "walk/vpls/quasi_random_walk.h"

#include <memory>
#include <string>
#include <vector>

namespace irad {

enum class WalkMode { Ring, Cached, Reshade };
WalkMode parse_walk_mode(const std::string& name);
const char* walk_mode_name(WalkMode mode);
// The default ("auto"): ring while the camera stands still (then it draws what cached draws, 7x
// faster), cached when the camera moves (glTF camera animation or an orbit): on the animated
// Cornell box's fly-through cached halves the ring's error against converged frames
// (docs/walkthrough.md).
WalkMode default_walk_mode(const Scene& scene, std::size_t camera, float orbit);

struct WalkthroughSettings {
  WalkMode mode = WalkMode::Ring;
  std::uint32_t paths = 64; // N
  int width = 256, height = 256;
  float fps = 30.0f;
  float orbit = 0.0f; // camera orbit about the vertical axis, degrees per second
  GlBackend backend = GlBackend::Auto;
  int interleave = 4; // cached and reshade modes (RasterOptions::interleave)
};

class Walkthrough {
public:
  // `scene` is posed in place; `camera` indexes scene.cameras.
  Walkthrough(Scene& scene, std::size_t camera, const WalkthroughSettings& settings, Log& log);

  // Traces paths 0..N-1 with the scene at frame `frame`'s time, so the first frame is converged.
  void warm_up(int frame);
  // Frame `frame` seen from the scene's (posed, orbited) camera.
  Image frame(int frame);
  // Frame `frame` seen from `camera` (interactive viewers move it themselves).
  Image frame(int frame, const Camera& camera);

  // The scene camera at frame `frame` (posed and orbited).
  Camera camera_at(int frame);
  std::uint32_t paths() const { return n_; }
  int l_max() const { return walk_.header().l_max; }
  std::string description() const;

private:
  void pose(int frame);
  void trace(std::uint32_t slot, const View& view);
  VplSet all_vpls() const; // the N paths' VPLs

  Scene& scene_;
  std::size_t camera_;
  WalkthroughSettings settings_;
  RayScene rays_;
  QuasiRandomWalk walk_;
  std::uint32_t n_;
  std::unique_ptr<RingRenderer> ring_;
  std::unique_ptr<RasterRenderer> raster_;
  std::vector<std::vector<Vpl>> vpls_;      // per slot: the path's VPLs
  std::vector<std::vector<VplLobe>> lobes_; // per slot: what its glossy VPLs index
  std::uint32_t next_ = 0;                  // frames traced; the next replaces slot next_ mod N
  int posed_frame_ = -1;
};

} // namespace irad
