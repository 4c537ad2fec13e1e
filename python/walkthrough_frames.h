#pragma once
// irad.walkthrough: the library's Walkthrough session (lib/irad/walkthrough.h) as a Python
// iterator of frames, each a float32 array (h, w, 3). The session owns a copy of the scene (the
// animation poses it in place) and its GL context; iterate it on the thread that created it.
#include "core/scene/scene.h"
#include "core/util/log.h"
#include "irad/walkthrough.h"

#include <memory>
#include <pybind11/numpy.h>
#include <string>
#include <utility>

namespace irad::python {

struct WalkthroughKeywords {
  std::pair<int, int> frames{0, 60}; // A:B, B exclusive
  std::string mode = "auto";         // auto, ring, cached, reshade
  std::uint32_t paths = 64;
  std::pair<int, int> size{256, 256};
  float fps = 30.0f;
  float orbit = 0.0f; // degrees per second
  std::string camera;
  std::string gl = "auto";
  bool warm_up = true; // the first frame already shows N paths
};

class WalkthroughFrames {
public:
  // Throws irad::Error naming the keyword for a bad value.
  WalkthroughFrames(const Scene& scene, const WalkthroughKeywords& keywords);
  // The next frame (GIL released while it renders); throws pybind11::stop_iteration after B-1.
  pybind11::array next();
  const char* mode() const { return walk_mode_name(mode_); }
  std::uint32_t paths() const { return walk_->paths(); }

private:
  Log log_;
  std::unique_ptr<Scene> scene_; // posed in place by the session
  WalkMode mode_;
  int frame_, last_;
  bool warm_ = false, warm_up_;
  std::unique_ptr<Walkthrough> walk_;
};

} // namespace irad::python
