#include "raster/raster_renderer.h"

#include "core/error.h"
#include "core/rng.h"
#include "raster/camera_passes.h"
#include "raster/gl_context.h"
#include "raster/gpu_scene.h"
#include "raster/interleaved.h"
#include "raster/pass_timer.h"
#include "raster/shadow_cube.h"
#include "raster/target.h"
#include "raster/vpl_shader.h"

#include <algorithm>
#include <chrono>
#include <optional>

namespace irad {

namespace {

using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

bool carries_light(const Vpl& v) {
  return v.intensity.x > 0.0f || v.intensity.y > 0.0f || v.intensity.z > 0.0f;
}

// The interleaved set of a particle: a hash of its index, so every set holds a random share of
// each reflection depth. Measured against the alternatives: i mod k^2 fixes the leading base-2
// digits of Phi_2(i) within a set (every set lights from one strip of the light: 4x the error at
// the light's silhouette in RasterAnalytic.InterleavedSquareLightOverPlaneMatchesLambert);
// contiguous segments of the paths leave the deep reflections to the first set (few particles
// reach them), which the resolve cannot average where its window is cut by geometry: relMSE
// 7.0e-4 against 8.0e-5 with the hash on the integrating sphere (128x128, N = 256).
int set_of(std::uint32_t path, int sets) {
  return static_cast<int>(mix64(path) % static_cast<std::uint64_t>(sets));
}

} // namespace

int shadow_resolution_for(int requested, int width, int height) {
  if (requested > 0) return requested;
  // A cube face spans 90 degrees; a quarter of the image's larger side per face edge (rounded up
  // to a power of two, 64..1024) kept the shadow-map error of the Cornell box 20x below its total
  // error at 256x256 (relMSE 2.5e-4 against 5.3e-3, docs/accuracy.md).
  int r = 64;
  while (r < 1024 && r < std::max(width, height) / 4) r *= 2;
  return r;
}

struct RasterRenderer::Impl {
  const Scene& scene;
  RasterOptions options;
  std::unique_ptr<gl::Context> context;
  const GladGLContext& api;
  gl::GpuScene gpu;
  std::unique_ptr<gl::ShadowCube> shadow;
  gl::CameraPasses camera;
  gl::VplShader vpl_shader;
  std::unique_ptr<gl::Target> target;
  std::unique_ptr<gl::Interleaved> interleaved;

  Impl(const Scene& s, const RasterOptions& o, std::unique_ptr<gl::Context> c)
      : scene(s), options(o), context(std::move(c)), api(context->api()), gpu(api, s), camera(api),
        vpl_shader(api, s, o.clamp) {
    context->check("raster set-up");
  }

  void prepare(const View& view);
  // The VPL passes, each VPL shadow map then shading; returns the number drawn.
  std::size_t vpl_passes(const View& view, const VplSet& vpls, gl::PassTimer* timer,
                         const Progress& progress);
};

void RasterRenderer::Impl::prepare(const View& view) {
  if (!target || target->width() != view.width || target->height() != view.height) {
    interleaved.reset();
    target = std::make_unique<gl::Target>(api, view.width, view.height);
  }
  const int resolution = shadow_resolution_for(options.shadow_resolution, view.width, view.height);
  if (!shadow || shadow->resolution() != resolution)
    shadow = std::make_unique<gl::ShadowCube>(api, resolution, scene.bounds);
  if (options.interleave > 1 && !interleaved)
    interleaved = std::make_unique<gl::Interleaved>(api, view.width, view.height,
                                                    options.interleave, target->depth());
}

std::size_t RasterRenderer::Impl::vpl_passes(const View& view, const VplSet& vpls,
                                             gl::PassTimer* timer, const Progress& progress) {
  const glm::mat4 vp = view.projection * view.view;
  std::vector<glm::mat4> tile_vp;
  if (interleaved)
    for (int s = 0; s < interleaved->sets(); ++s)
      tile_vp.push_back(interleaved->tile_projection(s, view.projection) * view.view);
  std::size_t passes = 0;
  for (std::size_t k = 0; k < vpls.vpls.size(); ++k) {
    if (options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed)) break;
    const Vpl& vpl = vpls.vpls[k];
    if (carries_light(vpl)) {
      if (timer) timer->begin(gl::PassTimer::Shadow);
      const glm::mat3 frame = shadow->render(vpl, gpu);
      if (timer) timer->end();
      if (timer) timer->begin(gl::PassTimer::Shading);
      if (interleaved) {
        const int set = set_of(vpl.path, static_cast<int>(tile_vp.size()));
        interleaved->bind_tile(set);
        vpl_shader.draw(vpl, *shadow, frame, tile_vp[static_cast<std::size_t>(set)], false, gpu);
      } else {
        target->bind();
        vpl_shader.draw(vpl, *shadow, frame, vp, true, gpu);
      }
      if (timer) timer->end();
      ++passes;
    }
    if (progress) progress(k + 1, vpls.vpls.size());
  }
  return passes;
}

RasterRenderer::RasterRenderer(const Scene& scene, const RasterOptions& options) {
  if (options.shadow_resolution < 0 || options.shadow_resolution > 8192)
    throw Error("", "--shadow-res", "must be between 1 and 8192 (0: automatic)");
  if (!(options.clamp >= 0.0f)) throw Error("", "--clamp", "must be >= 0");
  if (options.interleave < 1 || options.interleave > 16)
    throw Error("", "--interleave", "must be between 1 and 16");
  auto context = gl::create_context(options.backend, options.gl_device);
  if (options.gl_messages) context->route_debug_messages(options.gl_messages);
  impl_ = std::make_unique<Impl>(scene, options, std::move(context));
  impl_->context->release();
}

// The GL objects are deleted in their own context.
RasterRenderer::~RasterRenderer() {
  try {
    if (impl_) impl_->context->make_current();
  } catch (const std::exception&) { // then they are deleted with the context
  }
}

std::string RasterRenderer::description() const {
  const gl::CurrentScope current(*impl_->context);
  return impl_->context->backend() + ": " + impl_->context->renderer();
}

Image RasterRenderer::render(const View& view, const VplSet& vpls, RasterTimings* timings,
                             const Progress& progress) {
  Impl& im = *impl_;
  const auto t0 = Clock::now();
  const gl::CurrentScope current(*im.context);
  im.prepare(view);
  const glm::mat4 vp = view.projection * view.view;
  if (im.interleaved) {
    // The full-resolution G-buffer (its depth is the target's), then each set's depth in its tile.
    im.interleaved->bind_gbuffer();
    im.camera.gbuffer(vp, im.gpu);
    im.interleaved->bind_atlas();
    im.api.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    im.api.ClearDepth(1.0);
    im.api.DepthMask(GL_TRUE);
    im.api.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    for (int s = 0; s < im.interleaved->sets(); ++s) {
      im.interleaved->bind_tile(s);
      im.camera.depth(im.interleaved->tile_projection(s, view.projection) * view.view, im.gpu);
    }
  } else {
    im.target->bind();
    im.api.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    im.api.ClearDepth(1.0);
    im.api.DepthMask(GL_TRUE);
    im.api.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    im.camera.depth(vp, im.gpu);
  }
  std::optional<gl::PassTimer> timer;
  if (im.options.gpu_timers) timer.emplace(im.api);
  const std::size_t passes = im.vpl_passes(view, vpls, timer ? &*timer : nullptr, progress);
  im.target->bind();
  if (im.interleaved) im.interleaved->resolve();
  im.camera.emitters(vp, im.scene, im.gpu);
  im.context->check("raster passes");
  const auto t1 = Clock::now();
  Image image = im.target->read();
  im.context->check("readback");
  if (timings) {
    timings->passes_seconds = seconds(t0, t1);
    timings->readback = seconds(t1, Clock::now());
    timings->passes = passes;
    if (timer) {
      const auto gpu = timer->seconds();
      timings->shadow_gpu = gpu[gl::PassTimer::Shadow];
      timings->shading_gpu = gpu[gl::PassTimer::Shading];
    }
  }
  return image;
}

} // namespace irad
