#pragma once
// The instant radiosity rasterizer (design.md section 1, "Rasterization"): for every VPL a cube
// shadow map and a shading pass that adds w * C(x) into an RGBA32F framebuffer; the visible
// emitters' L_e once; then readback. Public header: no GL types.
#include "core/image.h"
#include "core/scene.h"
#include "core/view.h"
#include "core/vpl.h"

#include <functional>
#include <memory>

namespace irad {

// Which OpenGL: auto (a GPU through EGL when there is one, else OSMesa, else EGL surfaceless),
// egl (a device, or Mesa's surfaceless platform) or osmesa.
enum class GlBackend { Auto, Egl, OsMesa };

struct RasterOptions {
  int shadow_resolution = 256; // texels per cube face edge
  float clamp = 0.05f;         // d_min as a fraction of the scene's bounding diagonal
  GlBackend backend = GlBackend::Auto;
  int gl_device = -1;      // EGL device index; -1: the first hardware device
  bool gpu_timers = false; // split the time between shadow maps and shading (benchmarks)
};

struct RasterTimings {
  double passes_seconds = 0.0; // wall clock: shadow maps, shading passes and emitters
  double readback = 0.0;       // wall clock: the final readback (waits for the GPU)
  std::size_t passes = 0;      // VPLs drawn
  // GPU time of the shadow-map and shading passes (GL_TIME_ELAPSED), only with gpu_timers.
  double shadow_gpu = -1.0;
  double shading_gpu = -1.0;
};

using Progress = std::function<void(std::size_t done, std::size_t total)>;

class RasterRenderer {
public:
  // Creates an OSMesa context and uploads the scene. Throws irad::Error on any GL failure.
  RasterRenderer(const Scene& scene, const RasterOptions& options);
  ~RasterRenderer();
  RasterRenderer(const RasterRenderer&) = delete;
  RasterRenderer& operator=(const RasterRenderer&) = delete;

  // pixel(x) = L_e(x) + sum_k C_k(x) over the VPLs, for the given view. Alpha is 1.
  Image render(const View& view, const VplSet& vpls, RasterTimings* timings = nullptr,
               const Progress& progress = {});

  std::string description() const; // backend and GL renderer

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace irad
