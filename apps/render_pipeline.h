#pragma once
// load -> walk -> raster, the path every rendering subcommand takes, with per-stage times.
#include "core/environment/lighting.h"
#include "core/gltf/loader.h"
#include "core/image.h"
#include "core/log.h"
#include "core/scene.h"
#include "core/view.h"
#include "core/vpl.h"
#include "raster/raster_renderer.h"
#include "walk/path_tracer.h"
#include "walk/quasi_random_walk.h"

#include <atomic>
#include <optional>
#include <string>

namespace irad::apps {

// raster: the instant radiosity rasterizer; rt-vpl: the same VPLs with exact (ray-traced)
// visibility; pt: the path-traced reference.
enum class Estimator { Raster, RtVpl, Pt };

struct RenderRequest {
  Estimator estimator = Estimator::Raster;
  std::string scene_path;
  std::optional<std::pair<int, int>> size; // WxH; default from the camera's aspect, 512 high
  std::string camera;                      // name or index; empty: the first camera
  std::string gltf_scene;                  // --scene: a glTF scene by name or index (empty: the
                                           // file's default scene)
  std::optional<Camera> own_camera; // --look-from...: replaces the file's cameras (use_own_camera)
  std::optional<float> time;        // seconds: pose the scene's glTF animation (else the rest pose)
  WalkOptions walk;
  RasterOptions raster;           // clamp and shadow resolution (clamp also for rt-vpl)
  PathTracerOptions pt;           // spp, seed, threads
  bool bias_compensation = false; // add the clamp's residual (walk/bias_compensation.h)
  std::uint32_t bias_samples = 16;
  bool clamped_fraction = false; // estimate the share of light the clamp removes
  bool progress = false;         // a progress line on stderr
  LoadLimits limits;             // scene size limits (core/gltf/loader.h)
  LightingOptions lighting;      // the environment (core/environment/lighting.h)
  // When it becomes true (a signal handler), the render stops early: no further stage starts,
  // the running one returns what it has, and the result says cancelled.
  const std::atomic<bool>* cancel = nullptr;
};

struct StageSeconds {
  // trace: pt and rt-vpl, or the raster's ray-traced pass over visible mirrors
  double load = 0, walk = 0, raster = 0, readback = 0, trace = 0, compensation = 0, total = 0;
};

struct RenderResult {
  Scene scene;
  Camera camera;
  View view;
  VplSet vpls;
  Image
      image; // when cancelled: what was accumulated (pt, rt-vpl: pixels not done are 0, alpha too)
  StageSeconds seconds;
  bool cancelled = false;         // stopped early by request.cancel
  std::size_t passes = 0;         // VPL passes drawn (raster)
  double clamped_fraction = -1.0; // when requested
  std::string gl;                 // GL renderer (raster)
};

RenderResult render_scene(const RenderRequest& request, Log& log);

// The camera selected by name or index (throws irad::Error listing the choices).
const Camera& select_camera(const Scene& scene, const std::string& which);
// Replaces the scene's cameras by `camera`, which the animation (if any) does not move.
void use_own_camera(Scene& scene, const Camera& camera);
// Image size: the request's, else 512 high with the camera's aspect (512x512 without one).
std::pair<int, int> image_size(const Camera& camera, std::optional<std::pair<int, int>> size);

} // namespace irad::apps
