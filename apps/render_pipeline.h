#pragma once
// load -> walk -> raster, the path every rendering subcommand takes, with per-stage times.
#include "core/image.h"
#include "core/log.h"
#include "core/scene.h"
#include "core/view.h"
#include "core/vpl.h"
#include "raster/raster_renderer.h"
#include "walk/quasi_random_walk.h"

#include <optional>
#include <string>

namespace irad::apps {

struct RenderRequest {
  std::string scene_path;
  std::optional<std::pair<int, int>> size; // WxH; default from the camera's aspect, 512 high
  std::string camera;                      // name or index; empty: the first camera
  WalkOptions walk;
  RasterOptions raster;
  bool progress = false; // a progress line on stderr
};

struct StageSeconds {
  double load = 0, walk = 0, raster = 0, readback = 0, total = 0;
};

struct RenderResult {
  Scene scene;
  Camera camera;
  View view;
  VplSet vpls;
  Image image;
  StageSeconds seconds;
  std::size_t passes = 0;
  std::string gl;
};

RenderResult render_scene(const RenderRequest& request, Log& log);

// The camera selected by name or index (throws irad::Error listing the choices).
const Camera& select_camera(const Scene& scene, const std::string& which);
// Image size: the request's, else 512 high with the camera's aspect (512x512 without one).
std::pair<int, int> image_size(const Camera& camera, std::optional<std::pair<int, int>> size);

} // namespace irad::apps
