#include "walkthrough_frames.h"

#include "arrays.h"
#include "core/util/error.h"
#include "irad/scene_setup.h"

#include <fmt/format.h>

namespace py = pybind11;

namespace irad::python {

namespace {

GlBackend backend_named(const std::string& name) {
  if (name == "auto") return GlBackend::Auto;
  if (name == "egl") return GlBackend::Egl;
  if (name == "osmesa") return GlBackend::OsMesa;
  throw Error("", "gl", "'" + name + "' is not auto, egl or osmesa");
}

void check(const WalkthroughKeywords& k) {
  const auto [a, b] = k.frames;
  if (a < 0 || b <= a)
    throw Error("", "frames", fmt::format("({}, {}) is not (A, B) with 0 <= A < B", a, b));
  const auto [w, h] = k.size;
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    throw Error("", "size", fmt::format("({}, {}) is out of range (1..16384 per side)", w, h));
  if (k.paths == 0) throw Error("", "paths", "must be at least 1");
}

} // namespace

WalkthroughFrames::WalkthroughFrames(const Scene& scene, const WalkthroughKeywords& k)
    : scene_(std::make_unique<Scene>(scene)), frame_(k.frames.first), last_(k.frames.second),
      warm_up_(k.warm_up) {
  check(k);
  const Camera& chosen = select_camera(*scene_, k.camera);
  const auto camera = static_cast<std::size_t>(&chosen - scene_->cameras.data());
  mode_ = k.mode == "auto" ? default_walk_mode(*scene_, camera, k.orbit) : parse_walk_mode(k.mode);
  WalkthroughSettings settings;
  settings.mode = mode_;
  settings.paths = k.paths;
  std::tie(settings.width, settings.height) = k.size;
  settings.fps = k.fps;
  settings.orbit = k.orbit;
  settings.backend = backend_named(k.gl);
  py::gil_scoped_release released;
  walk_ = std::make_unique<Walkthrough>(*scene_, camera, settings, log_);
}

py::array WalkthroughFrames::next() {
  if (frame_ >= last_) throw py::stop_iteration();
  Image image;
  {
    py::gil_scoped_release released;
    if (warm_up_ && !warm_) walk_->warm_up(frame_);
    warm_ = true;
    image = walk_->frame(frame_);
  }
  ++frame_;
  return to_array(image, 3);
}

} // namespace irad::python
