#pragma once
// RasterRenderer's state, shared by raster/raster_renderer.cpp (an image's passes) and
// raster/kept_shadow_maps.cpp (the shadow maps kept per path, render_cached). Private to raster/.
#include "raster/raster_renderer.h"

#include "core/lights/interleave_sets.h"
#include "core/sampling/rng.h"
#include "core/util/error.h"
#include "raster/context/gl_context.h"
#include "raster/context/pass_timer.h"
#include "raster/image/gbuffer.h"
#include "raster/image/interleaved.h"
#include "raster/image/jitter_passes.h"
#include "raster/image/pixel_jitter.h"
#include "raster/image/target.h"
#include "raster/passes/background.h"
#include "raster/passes/batched_passes.h"
#include "raster/passes/camera_passes.h"
#include "raster/passes/directional_pass.h"
#include "raster/passes/vpl_shader.h"
#include "raster/scene/gpu_scene.h"
#include "raster/shadow/lod_provider.h"
#include "raster/shadow/shadow_cache.h"
#include "raster/shadow/shadow_cube.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
#include <optional>
#include <thread>

namespace irad {

using Clock = std::chrono::steady_clock;
inline double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// What the deferred passes shade, by the G-buffer they read: cell s < kJitterStrata the one
// drawn at that jitter cell's centre, cell kJitterStrata the image's own (the pixel centre).
template <class T>
using JitterCells = std::array<std::vector<T>, kJitterStrata + 1>;

// `items` by the jitter cell of their VPL (vpl_of(item), raster/image/pixel_jitter.h); without
// jitter all of them, unmoved, in the image's own cell.
template <class T, class VplOf>
JitterCells<T> jitter_cells(bool jitter, std::vector<T> items, const VplOf& vpl_of) {
  JitterCells<T> cells;
  if (!jitter) {
    cells[kJitterStrata] = std::move(items);
    return cells;
  }
  for (const T& item : items)
    cells[static_cast<std::size_t>(jitter_stratum(vpl_of(item)))].push_back(item);
  return cells;
}

struct RasterRenderer::Impl {
  const Scene& scene;
  RasterOptions options;
  std::unique_ptr<gl::Context> context;
  const GladGLContext& api;
  gl::GpuScene gpu;
  gl::LodProvider lod; // the batched passes' shadow hierarchy, kept when they are re-made
  gl::CameraLodProvider camera_lod; // the camera's, where camera_lod_wanted
  StageTimes setup_times;           // the GL context and the upload (RasterRenderer::setup_times)
  std::unique_ptr<gl::ShadowCube> shadow; // the per-VPL passes' cube, made on first use
  int shadow_res = 0;                     // this image's cube resolution
  gl::CameraPasses camera;
  gl::VplShader vpl_shader;
  std::unique_ptr<gl::Target> target;
  std::unique_ptr<gl::GBuffer> gbuffer; // for the batched passes and the interleaved resolve
  std::unique_ptr<gl::Interleaved> interleaved;
  InterleaveSets interleave_sets; // this image's paths dealt to the interleaved sets
  bool tile_depths = false;       // interleaved: each set's depth drawn in its tile for this image
  std::size_t single_passes = 0;  // this image's VPLs drawn by vpl_passes
  const gl::CameraLod* image_lod = nullptr;         // what this image's G-buffer and emitters draw
  std::unique_ptr<gl::JitterPasses> jitter;         // with options.jitter
  std::unique_ptr<gl::DirectionalPass> directional; // only for scenes with directional lights
  std::unique_ptr<gl::BatchedPasses> batched;       // options.batch > 1
  std::unique_ptr<gl::Background> background;       // only for scenes that show one
  // Shadow maps kept per path slot (render_cached). Batched: the slot's VPLs in the atlas pages
  // of shadow_cache, the directional ones drawn by the batched passes per image (their
  // orthographic maps are cheap: one per direction). The per-VPL reference (batch 1) keeps a
  // cube per VPL and draws a directional VPL's map per image.
  struct CachedPath {
    std::vector<Vpl> vpls; // those shaded per VPL
    std::vector<gl::Texture> cubes;
    std::vector<glm::mat3> frames;
    std::vector<Vpl> directional; // batched: drawn anew per image
    std::vector<VplLobe> lobes;   // what the path's glossy VPLs index (Vpl::lobe)
  };
  std::vector<CachedPath> cache;
  std::uint32_t cached_paths = 0; // past the largest slot and path index cached so far
  std::unique_ptr<gl::ShadowCube> cache_shadow;  // draws into the cached cubes
  std::unique_ptr<gl::ShadowCache> shadow_cache; // batched: the kept atlas blocks

  Impl(const Scene& s, const RasterOptions& o, std::unique_ptr<gl::Context> c)
      : scene(s), options(o), context(std::move(c)), api(context->api()), gpu(api, s),
        lod(api, gpu, o.shadow_lod, o.hierarchy_cache, o.hierarchy_build),
        camera_lod(api, gpu, o.hierarchy_cache, o.camera_build), camera(api, gpu.features()),
        vpl_shader(api, s, o.clamp, drawn_lod().planes != ShadowPlanes::Off), // options set
        jitter(o.jitter ? std::make_unique<gl::JitterPasses>(api, gpu.features()) : nullptr),
        background(gl::Background::make(api, s)) {
    context->check("raster set-up");
  }

  void prepare(const View& view);
  // Whether the occluder planes wait for RasterOptions::choose_planes (Auto with a chooser, not
  // asked yet): until then nothing draws or reads them, as with Off.
  static bool planes_pending(const RasterOptions& o) {
    return o.shadow_lod.planes == ShadowPlanes::Auto && o.choose_planes != nullptr;
  }
  // The batched passes' level-of-detail options as drawn now (planes Off while pending).
  ShadowLodOptions drawn_lod() const {
    ShadowLodOptions drawn = options.shadow_lod;
    if (planes_pending(options)) drawn.planes = ShadowPlanes::Off;
    return drawn;
  }
  // Shadow maps are about to be drawn to shade: a pending choice of the occluder planes is asked
  // now (once), and the per-VPL shader and the batched passes draw what it answered.
  void settle_planes();
  // Whether rays may answer visibility here (RasterOptions::visibility): asked for, or Auto on a
  // CPU renderer, with a tracer and options that allow them.
  bool rays_allowed() const {
    if (options.visibility == Visibility::Maps || !options.visibility_tracer ||
        rays_refused(options) != nullptr)
      return false;
    return options.visibility == Visibility::Rays || context->cpu_renderer();
  }
  // RasterOptions::shadow_helpers, auto resolved for this context.
  int shadow_helpers() const {
    if (options.shadow_helpers >= 0) return options.shadow_helpers;
    // One core cannot bin one atlas while it rasterizes another.
    return context->cpu_renderer() && std::thread::hardware_concurrency() >= 2 ? 2 : 0;
  }
  // This image's interleaved sets for paths 0..paths-1 (one set without interleaving).
  void deal_paths(std::uint32_t paths) {
    interleave_sets = InterleaveSets(paths, interleaved ? interleaved->sets() : 1);
  }
  // The batched passes for a width x height image (batch > 1, no jitter, a GL that fits them).
  void ensure_batched(int width, int height);
  // Clears the target and draws what every VPL pass adds to: the G-buffer (batched or
  // interleaved) or else the visible surface's depth.
  void begin_image(const View& view);
  // Interleaved: each set's depth in its tile, which the per-VPL passes test against (drawn once
  // per image, only when such a pass comes).
  void ensure_tile_depths(const View& view);
  // A VPL pass needs its shadow cube: drawn now (render) or kept from before (render_cached).
  using ShadowFor = std::function<GLuint(std::size_t k, glm::mat3& frame)>;
  // The VPL passes of vpls[k] for every k, each VPL's shadow map then shading; returns the number
  // drawn.
  std::size_t vpl_passes(const View& view, const std::vector<const Vpl*>& vpls,
                         const ShadowFor& shadow_for, float texel_angle, gl::PassTimer* timer,
                         const Progress& progress);
  // vpl_passes with the VPLs drawn in batches (raster/passes/batched_passes.h), directional ones
  // alone.
  std::size_t batched_passes(const View& view, const std::vector<const Vpl*>& vpls,
                             gl::PassTimer* timer, const Progress& progress);
  // Binds the VPL's framebuffer and viewport and returns the view-projection it is shaded with;
  // with jitter, the depth there is redrawn for its offset when that differs from the last one.
  glm::mat4 bind_pass(const View& view, const Vpl& vpl, std::vector<glm::vec2>& last_offsets);
  // The orthographic shadow map of a directional VPL (shared by the VPLs of one direction).
  void directional_shadow(const Vpl& vpl) { directional->shadow(vpl, gpu); }
  // A per-VPL pass's shadow map drawn now (ShadowFor): the VPL's cube, or for a directional VPL
  // its orthographic map (0 returned, frame untouched).
  GLuint shadow_now(const Vpl& vpl, glm::mat3& frame);
  float texel_angle() const { return 2.0f / static_cast<float>(shadow_res); }
  gl::DeferredTarget deferred_target() const {
    return {gbuffer.get(), interleaved.get(), [t = target.get()] { t->bind(); },
            interleaved && interleaved->has_receiver_mask()};
  }
  // For every cell s (JitterCells) with used[s], in order, shade(target, s) with the target
  // reading the cell's G-buffer (drawn now for a jitter cell), until shade returns false.
  using ShadeInto = std::function<bool(const gl::DeferredTarget&, std::size_t cell)>;
  void by_cell(const View& view, const std::array<bool, kJitterStrata + 1>& used,
               const ShadeInto& shade);
  // render_cached's batched passes: the kept atlas pages and the directional VPLs (their maps
  // drawn now), with jitter cell by cell. Returns the number of VPLs shaded.
  std::size_t shade_kept(const View& view);
  // The resolve (interleaved), the emitters, the background and the readback.
  Image finish_image(const View& view, Clock::time_point t0, std::size_t passes,
                     gl::PassTimer* timer, RasterTimings* timings);
};

} // namespace irad
