#pragma once
// irad.render and irad.walk: Python's keywords as irad::RenderOptions, the work with the GIL
// released, and the results as NumPy arrays and dicts. The bindings add no logic of their own:
// everything is irad::render (lib/irad/render.h) and irad::quasi_random_walk.
#include "core/scene/scene.h"
#include "irad/render.h"

#include <pybind11/numpy.h>
#include <pybind11/pytypes.h>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>

namespace irad::python {

// The keywords of irad.render, with the CLI's defaults.
struct RenderKeywords {
  std::optional<std::pair<int, int>> size; // (width, height); None: the camera's aspect, 512 high
  std::optional<std::uint32_t> paths; // None: auto (the light budget, core/lights/light_budget.h)
  std::string estimator = "raster";
  std::uint32_t spp = 64;
  std::uint64_t seed = 0;
  float clamp = 0.05f;
  std::optional<int> interleave; // None: auto (lib/irad/render.h)
  int batch = 64;
  int shadow_res = 0;
  std::string sequence = "halton";
  bool jitter = false;
  std::string camera; // name or index; empty: the first
  std::optional<float> time;
  unsigned threads = 0;
  bool bias_compensation = false;
  std::string gl = "auto";
  std::optional<std::size_t> clusters;   // RenderOptions::clusters (0: every VPL); None: auto
  std::uint32_t rounds = 1;              // RenderOptions::rounds
  std::string interleave_edges = "auto"; // auto, traced, shaded, off (irad render's option)
  float traced_roughness = RenderOptions{}.traced_roughness;     // --traced-roughness
  std::uint32_t glossy_samples = RenderOptions{}.glossy_samples; // --glossy-samples
  std::string visibility = "auto"; // auto, maps, rays (irad render's --visibility)
};

// (image float32 (h, w, 3), stats dict). The GIL is released while rendering; Ctrl-C (SIGINT
// in the main thread) cancels the render and raises KeyboardInterrupt. Bad keywords raise
// irad.Error naming them.
pybind11::tuple render(const Scene& scene, const RenderKeywords& keywords);

// (VPLs as a structured array: position, normal, intensity (3 x float32 each), kind (uint8:
// 0 surface, 1 two-sided, 2 point, 3 spot, 4 directional), depth (uint16), path (uint32);
// stats dict: paths, rho_bar, l_max, planned, depth_capped).
pybind11::tuple walk(const Scene& scene, std::uint32_t paths, const std::string& sequence,
                     std::uint64_t seed);

} // namespace irad::python
