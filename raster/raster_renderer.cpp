#include "raster/raster_renderer.h"

#include "core/error.h"
#include "core/rng.h"
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
#include "raster/shadow/shadow_cache.h"
#include "raster/shadow/shadow_cube.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
#include <optional>

namespace irad {

namespace {

using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
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

float planes_reach(int resolution) {
  return 4.0f / static_cast<float>(std::max(resolution, 1)) + 2e-4f;
}

bool planes_needed(float thinnest_wall, int resolution) {
  return thinnest_wall < planes_reach(resolution);
}

struct RasterRenderer::Impl {
  const Scene& scene;
  RasterOptions options;
  std::unique_ptr<gl::Context> context;
  const GladGLContext& api;
  gl::GpuScene gpu;
  std::unique_ptr<gl::ShadowCube> shadow; // the per-VPL passes' cube, made on first use
  int shadow_res = 0;                     // this image's cube resolution
  gl::CameraPasses camera;
  gl::VplShader vpl_shader;
  std::unique_ptr<gl::Target> target;
  std::unique_ptr<gl::GBuffer> gbuffer; // for the batched passes and the interleaved resolve
  std::unique_ptr<gl::Interleaved> interleaved;
  bool tile_depths = false;      // interleaved: each set's depth drawn in its tile for this image
  std::size_t single_passes = 0; // this image's VPLs drawn by vpl_passes
  std::unique_ptr<gl::JitterPasses> jitter;         // with options.jitter
  std::unique_ptr<gl::DirectionalPass> directional; // only for scenes with directional lights
  std::unique_ptr<gl::BatchedPasses> batched;       // options.batch > 1, no jitter
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
  };
  std::vector<CachedPath> cache;
  std::unique_ptr<gl::ShadowCube> cache_shadow;  // draws into the cached cubes
  std::unique_ptr<gl::ShadowCache> shadow_cache; // batched: the kept atlas blocks

  Impl(const Scene& s, const RasterOptions& o, std::unique_ptr<gl::Context> c)
      : scene(s), options(o), context(std::move(c)), api(context->api()), gpu(api, s),
        camera(api, gpu.features()),
        vpl_shader(api, s, o.clamp, o.shadow_lod.planes != ShadowPlanes::Off),
        jitter(o.jitter ? std::make_unique<gl::JitterPasses>(api, gpu.features()) : nullptr),
        background(gl::Background::make(api, s)) {
    context->check("raster set-up");
  }

  void prepare(const View& view);
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
    return {gbuffer.get(), interleaved.get(), [t = target.get()] { t->bind(); }};
  }
  // The deferred passes' G-buffers: without jitter shade(deferred_target(), -1) once; with it,
  // for every jitter cell s with used[s] (raster/image/pixel_jitter.h), shade(target, s) reading
  // the cell's G-buffer, until shade returns false.
  using ShadeInto = std::function<bool(const gl::DeferredTarget&, int stratum)>;
  void by_stratum(const View& view, const std::array<bool, kJitterStrata + 1>& used,
                  const ShadeInto& shade);
  // render_cached's batched passes: the kept atlas pages and the directional VPLs (their maps
  // drawn now), with jitter cell by cell. Returns the number of VPLs shaded.
  std::size_t shade_kept(const View& view);
  // The resolve (interleaved), the emitters, the background and the readback.
  Image finish_image(const View& view, Clock::time_point t0, std::size_t passes,
                     gl::PassTimer* timer, RasterTimings* timings);
};

glm::mat4 RasterRenderer::Impl::bind_pass(const View& view, const Vpl& vpl,
                                          std::vector<glm::vec2>& last_offsets) {
  const int set = interleaved ? set_of(vpl.path, interleaved->sets()) : 0;
  if (interleaved)
    interleaved->bind_tile(set);
  else
    target->bind();
  glm::mat4 projection = view.projection;
  if (jitter) {
    const glm::vec2 offset = vpl_jitter(vpl);
    projection = jittered_projection(projection, offset, view.width, view.height);
    if (interleaved) projection = interleaved->tile_projection(set, projection);
    glm::vec2& last = last_offsets.at(static_cast<std::size_t>(set));
    if (offset != last) jitter->redraw_depth(camera, projection * view.view, gpu);
    last = offset;
  } else if (interleaved) {
    projection = interleaved->tile_projection(set, projection);
  }
  return projection * view.view;
}

void RasterRenderer::Impl::ensure_batched(int width, int height) {
  const int resolution = shadow_resolution_for(options.shadow_resolution, width, height);
  const int ortho = gl::has_directional_light(scene)
                        ? gl::ortho_resolution_for(options.shadow_resolution, width, height)
                        : 0;
  if (!batched || !batched->matches(options.batch, resolution, ortho))
    batched = gl::BatchedPasses::make(api, scene, options.clamp, options.batch, resolution, ortho,
                                      options.shadow_lod);
}

void RasterRenderer::Impl::prepare(const View& view) {
  const int resolution = shadow_resolution_for(options.shadow_resolution, view.width, view.height);
  ensure_batched(view.width, view.height);
  if (!target || target->width() != view.width || target->height() != view.height) {
    interleaved.reset();
    gbuffer.reset();
    target = std::make_unique<gl::Target>(api, view.width, view.height);
  }
  if ((batched || options.interleave > 1) && !gbuffer)
    gbuffer = std::make_unique<gl::GBuffer>(api, view.width, view.height, target->depth());
  shadow_res = resolution;
  if (options.interleave > 1 && !interleaved)
    interleaved = std::make_unique<gl::Interleaved>(api, options.interleave, *gbuffer);
  const int ortho = gl::ortho_resolution_for(options.shadow_resolution, view.width, view.height);
  if (gl::has_directional_light(scene) && (!directional || directional->resolution() != ortho))
    directional = std::make_unique<gl::DirectionalPass>(api, scene, ortho);
  if (directional) directional->forget();
}

std::size_t RasterRenderer::Impl::batched_passes(const View& view,
                                                 const std::vector<const Vpl*>& vpls,
                                                 gl::PassTimer* timer, const Progress& progress) {
  // Directional VPLs keep their own passes only when no orthographic atlas fits this GL.
  std::vector<const Vpl*> many, alone;
  for (const Vpl* v : vpls) {
    const bool own = v->kind == VplKind::Directional && !batched->directional();
    (own ? alone : many).push_back(v);
  }
  // VPLs of one direction next to each other (a directional light's, a sun's): the orthographic
  // map is drawn once per run of equal directions (raster/shadow/ortho_shadow.h), not once per
  // change (a sun's VPLs alternate with the sky's in path order). The sum does not depend on the
  // order.
  std::stable_sort(alone.begin(), alone.end(), [](const Vpl* a, const Vpl* b) {
    const bool da = a->kind == VplKind::Directional, db = b->kind == VplKind::Directional;
    if (da != db) return da;
    if (!da) return false;
    const glm::vec3 &p = a->normal, &q = b->normal;
    return p.x != q.x ? p.x < q.x : p.y != q.y ? p.y < q.y : p.z < q.z;
  });
  const int sets = interleaved ? interleaved->sets() : 1;
  // With jitter, the VPLs by jitter cell: one G-buffer each.
  std::array<std::vector<const Vpl*>, kJitterStrata + 1> cells;
  std::array<bool, kJitterStrata + 1> used{};
  if (jitter)
    for (const Vpl* v : many) {
      const auto s = static_cast<std::size_t>(jitter_stratum(*v));
      cells[s].push_back(v);
      used[s] = true;
    }
  std::size_t drawn = 0, before = 0;
  by_stratum(view, used, [&](const gl::DeferredTarget& into, int s) {
    const std::vector<const Vpl*>& some = s < 0 ? many : cells[static_cast<std::size_t>(s)];
    bool go = true;
    drawn += batched->draw(
        some, [&](const Vpl& v) { return set_of(v.path, sets); }, into, gpu, timer,
        [&](std::size_t done) {
          if (progress) progress(before + done, vpls.size());
          go = options.cancel == nullptr || !options.cancel->load(std::memory_order_relaxed);
          return go;
        });
    before += some.size();
    return go;
  });
  const auto draw_now = [&](std::size_t k, glm::mat3& frame) {
    return shadow_now(*alone[k], frame);
  };
  return drawn + vpl_passes(view, alone, draw_now, texel_angle(), timer, {});
}

GLuint RasterRenderer::Impl::shadow_now(const Vpl& vpl, glm::mat3& frame) {
  if (vpl.kind == VplKind::Directional) {
    directional_shadow(vpl);
    return 0;
  }
  if (!shadow || shadow->resolution() != shadow_res)
    shadow = std::make_unique<gl::ShadowCube>(api, shadow_res, scene.bounds, gpu.features());
  frame = shadow->render(vpl, gpu);
  return shadow->texture();
}

void RasterRenderer::Impl::by_stratum(const View& view,
                                      const std::array<bool, kJitterStrata + 1>& used,
                                      const ShadeInto& shade) {
  if (!jitter) {
    shade(deferred_target(), -1);
    return;
  }
  for (int s = 0; s <= kJitterStrata; ++s) {
    if (!used[static_cast<std::size_t>(s)]) continue;
    if (s == kJitterStrata) { // the pixel centre: the image's G-buffer
      if (!shade(deferred_target(), s)) return;
      continue;
    }
    const gl::GBuffer& cell = jitter->stratum_gbuffer(camera, view, s, gpu);
    if (!shade({&cell, interleaved.get(), [t = target.get()] { t->bind(); }}, s)) return;
  }
}

std::size_t RasterRenderer::Impl::vpl_passes(const View& view, const std::vector<const Vpl*>& vpls,
                                             const ShadowFor& shadow_for, float texel_angle,
                                             gl::PassTimer* timer, const Progress& progress) {
  if (!vpls.empty()) ensure_tile_depths(view);
  // The depth each framebuffer (or atlas tile) holds: the unjittered one (offset 0) at first.
  std::vector<glm::vec2> last_offsets(interleaved ? interleaved->sets() : 1, glm::vec2(0.0f));
  std::size_t passes = 0;
  for (std::size_t k = 0; k < vpls.size(); ++k) {
    if (options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed)) break;
    const Vpl& vpl = *vpls[k];
    if (vpl.carries_light()) {
      if (timer) timer->begin(gl::PassTimer::Shadow);
      glm::mat3 frame;
      const GLuint cube = shadow_for(k, frame);
      if (timer) timer->end();
      if (timer) timer->begin(gl::PassTimer::Shading);
      const glm::mat4 pass_vp = bind_pass(view, vpl, last_offsets);
      if (vpl.kind == VplKind::Directional)
        directional->draw(vpl, pass_vp, !interleaved, gpu); // its map: drawn by shadow_for
      else
        vpl_shader.draw(vpl, cube, texel_angle, frame, pass_vp, !interleaved, gpu);
      if (timer) timer->end();
      ++passes;
    }
    if (progress) progress(k + 1, vpls.size());
  }
  single_passes += passes;
  return passes;
}

void RasterRenderer::Impl::begin_image(const View& view) {
  prepare(view);
  const glm::mat4 vp = view.projection * view.view;
  api.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  api.ClearDepth(1.0);
  api.DepthMask(GL_TRUE);
  if (gbuffer) {
    // The full-resolution G-buffer; its depth is the target's.
    gbuffer->bind();
    camera.gbuffer(vp, gpu);
    if (jitter) jitter->average_albedo(camera, view, gpu);
  }
  tile_depths = false;
  single_passes = 0;
  api.DepthMask(GL_TRUE); // the passes above may leave it off
  if (interleaved) {
    interleaved->bind_atlas();
    api.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  } else {
    target->bind();
    api.Clear(gbuffer ? GL_COLOR_BUFFER_BIT : GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (!gbuffer) camera.depth(vp, gpu);
  }
}

void RasterRenderer::Impl::ensure_tile_depths(const View& view) {
  if (!interleaved || tile_depths) return;
  for (int s = 0; s < interleaved->sets(); ++s) {
    interleaved->bind_tile(s);
    camera.depth(interleaved->tile_projection(s, view.projection) * view.view, gpu);
  }
  tile_depths = true;
}

std::size_t RasterRenderer::Impl::shade_kept(const View& view) {
  const int sets = interleaved ? interleaved->sets() : 1;
  std::vector<gl::ShadowCache::Page> pages = shadow_cache->pages();
  std::vector<const Vpl*> directional_vpls;
  for (const CachedPath& p : cache)
    for (const Vpl& v : p.directional) directional_vpls.push_back(&v);
  std::array<bool, kJitterStrata + 1> used{};
  if (jitter) {
    for (const gl::ShadowCache::Page& page : pages)
      for (const gl::AtlasVpl& v : page.vpls)
        used[static_cast<std::size_t>(jitter_stratum(*v.vpl))] = true;
    for (const Vpl* v : directional_vpls) used[static_cast<std::size_t>(jitter_stratum(*v))] = true;
  }
  const auto in = [](const Vpl& v, int s) { return s < 0 || jitter_stratum(v) == s; };
  std::size_t passes = 0;
  by_stratum(view, used, [&](const gl::DeferredTarget& into, int s) {
    for (const gl::ShadowCache::Page& page : pages) {
      std::vector<gl::AtlasVpl> some;
      for (const gl::AtlasVpl& v : page.vpls)
        if (in(*v.vpl, s)) some.push_back(v);
      for (gl::AtlasVpl& v : some) v.set = set_of(v.vpl->path, sets);
      batched->shade(some, page.lookup, into);
      passes += some.size();
    }
    std::vector<const Vpl*> some;
    for (const Vpl* v : directional_vpls)
      if (in(*v, s)) some.push_back(v);
    passes += batched->draw(some, [&](const Vpl& v) { return set_of(v.path, sets); }, into, gpu,
                            nullptr, {});
    return true;
  });
  return passes;
}

Image RasterRenderer::Impl::finish_image(const View& view, Clock::time_point t0, std::size_t passes,
                                         gl::PassTimer* timer, RasterTimings* timings) {
  target->bind();
  if (interleaved) interleaved->resolve();
  if (jitter) {
    jitter->emitters(camera, view, scene, gpu, background.get());
  } else {
    camera.emitters(view.projection * view.view, scene, gpu);
    if (background) background->draw(view, view.projection * view.view);
  }
  context->check("raster passes");
  const auto t1 = Clock::now();
  Image image = target->read();
  context->check("readback");
  if (timings) {
    timings->passes_seconds = seconds(t0, t1);
    timings->readback = seconds(t1, Clock::now());
    timings->passes = passes;
    timings->single_passes = single_passes;
    if (timer) {
      const auto gpu_seconds = timer->seconds();
      timings->shadow_gpu = gpu_seconds[gl::PassTimer::Shadow];
      timings->shading_gpu = gpu_seconds[gl::PassTimer::Shading];
    }
  }
  return image;
}

void check_raster_options(const RasterOptions& options) {
  if (options.shadow_resolution < 0 || options.shadow_resolution > 8192)
    throw Error("", "--shadow-res", "must be between 1 and 8192 (0: automatic)");
  if (!(options.clamp >= 0.0f)) throw Error("", "--clamp", "must be >= 0");
  if (options.interleave < 1 || options.interleave > 16)
    throw Error("", "--interleave", "must be between 1 and 16");
  if (options.batch < 1 || options.batch > 256)
    throw Error("", "--batch", "must be between 1 and 256");
}

RasterRenderer::RasterRenderer(const Scene& scene, const RasterOptions& options) {
  check_raster_options(options);
  auto context = gl::create_context(options.backend, options.gl_device);
  if (options.gl_messages) context->route_debug_messages(options.gl_messages);
  impl_ = std::make_unique<Impl>(scene, options, std::move(context));
  impl_->context->release();
}

// The GL objects are deleted in their own context.
RasterRenderer::~RasterRenderer() {
  if (impl_) gl::make_current_for_teardown(*impl_->context);
}

void RasterRenderer::scene_changed() {
  const gl::CurrentScope current(*impl_->context);
  impl_->gpu.update_vertices();
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
  im.begin_image(view);
  std::optional<gl::PassTimer> timer;
  if (im.options.gpu_timers) timer.emplace(im.api);
  std::vector<const Vpl*> list;
  list.reserve(vpls.vpls.size());
  for (const Vpl& v : vpls.vpls) list.push_back(&v);
  const auto draw_now = [&](std::size_t k, glm::mat3& frame) {
    return im.shadow_now(*list[k], frame);
  };
  const std::size_t passes =
      im.batched ? im.batched_passes(view, list, timer ? &*timer : nullptr, progress)
                 : im.vpl_passes(view, list, draw_now, im.texel_angle(), timer ? &*timer : nullptr,
                                 progress);
  Image image = im.finish_image(view, t0, passes, timer ? &*timer : nullptr, timings);
  if (timings && im.batched) timings->shadow_triangles = im.batched->shadow_triangles();
  return image;
}

void RasterRenderer::cache_path(std::uint32_t slot, const std::vector<Vpl>& vpls, int width,
                                int height) {
  Impl& im = *impl_;
  const gl::CurrentScope current(*im.context);
  const int resolution = shadow_resolution_for(im.options.shadow_resolution, width, height);
  if (!im.cache_shadow || im.cache_shadow->resolution() != resolution) {
    im.cache.clear(); // cubes of another resolution
    im.shadow_cache.reset();
    im.cache_shadow =
        std::make_unique<gl::ShadowCube>(im.api, resolution, im.scene.bounds, im.gpu.features());
    // The batched passes shade kept atlas blocks; the reference (batch 1, jitter) keeps cubes.
    im.ensure_batched(width, height);
    if (im.batched)
      im.shadow_cache = std::make_unique<gl::ShadowCache>(
          im.api, resolution, gl::ShadowAtlas::capacity(im.api, resolution, im.options.batch),
          im.scene.bounds, im.gpu.features());
  }
  if (slot >= im.cache.size()) im.cache.resize(std::size_t(slot) + 1);
  Impl::CachedPath& path = im.cache[slot];
  // The slot's cubes are drawn over again: no texture allocation per frame once the ring is full.
  std::vector<gl::Texture> spare;
  for (gl::Texture& c : path.cubes)
    if (c.get() != 0) spare.push_back(std::move(c));
  path = {};
  std::vector<Vpl> in_atlas;
  for (const Vpl& v : vpls) {
    if (!v.carries_light()) continue;
    if (im.shadow_cache && v.kind != VplKind::Directional) {
      in_atlas.push_back(v);
      continue;
    }
    if (im.shadow_cache && im.batched && im.batched->directional()) {
      path.directional.push_back(v);
      continue;
    }
    path.vpls.push_back(v);
    if (v.kind == VplKind::Directional) { // its orthographic map is drawn per image
      path.cubes.emplace_back();
      path.frames.emplace_back(1.0f);
      continue;
    }
    if (spare.empty()) {
      path.cubes.push_back(gl::ShadowCube::make_cube(im.api, resolution));
    } else {
      path.cubes.push_back(std::move(spare.back()));
      spare.pop_back();
    }
    path.frames.push_back(im.cache_shadow->render_into(v, im.gpu, path.cubes.back().get()));
  }
  if (im.shadow_cache) im.shadow_cache->store(slot, in_atlas, im.gpu);
  im.context->check("cached shadow maps");
}

Image RasterRenderer::render_cached(const View& view, RasterTimings* timings) {
  Impl& im = *impl_;
  const auto t0 = Clock::now();
  const gl::CurrentScope current(*im.context);
  im.begin_image(view);
  std::size_t passes = 0;
  if (im.shadow_cache && im.batched) passes += im.shade_kept(view);
  std::vector<const Vpl*> list;
  std::vector<std::pair<GLuint, glm::mat3>> maps;
  for (const Impl::CachedPath& p : im.cache)
    for (std::size_t i = 0; i < p.vpls.size(); ++i) {
      list.push_back(&p.vpls[i]);
      maps.emplace_back(p.cubes[i].get(), p.frames[i]);
    }
  const auto kept = [&](std::size_t k, glm::mat3& frame) {
    if (list[k]->kind == VplKind::Directional) im.directional_shadow(*list[k]);
    frame = maps[k].second;
    return maps[k].first;
  };
  const float texel = im.cache_shadow ? im.cache_shadow->texel_angle() : 1.0f;
  passes += im.vpl_passes(view, list, kept, texel, nullptr, {});
  return im.finish_image(view, t0, passes, nullptr, timings);
}

std::size_t RasterRenderer::cache_bytes() const {
  std::size_t cubes = 0;
  for (const Impl::CachedPath& p : impl_->cache)
    for (const gl::Texture& c : p.cubes) cubes += c.get() != 0 ? 1 : 0;
  const std::size_t r = impl_->cache_shadow ? std::size_t(impl_->cache_shadow->resolution()) : 0;
  return cubes * 6 * r * r * sizeof(float) +
         (impl_->shadow_cache ? impl_->shadow_cache->bytes() : 0);
}

} // namespace irad
