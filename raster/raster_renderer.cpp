#include "raster/raster_renderer.h"

#include "core/util/error.h"
#include "raster/raster_renderer_impl.h"

namespace irad {

int shadow_resolution_for(int requested, int width, int height) {
  if (requested > 0) return requested;
  // A cube face spans 90 degrees; a quarter of the image's larger side per face edge (rounded up
  // to a power of two, 64..1024) keeps the shadow-map error of the Cornell box 20x below its total
  // error at 256x256 (relMSE 2.5e-4 against 5.3e-3, docs/accuracy.md).
  int r = 64;
  while (r < 1024 && r < std::max(width, height) / 4) r *= 2;
  return r;
}

float planes_reach(int resolution) {
  return 4.0f / static_cast<float>(std::max(resolution, 1)) + 2e-4f;
}

bool lists_unsure_pixels(const RasterOptions& options) {
  return options.edge_pixels == EdgePixelMode::Listed && options.interleave > 1;
}

bool planes_needed(float thinnest_wall, int resolution) {
  return thinnest_wall < planes_reach(resolution);
}

glm::mat4 RasterRenderer::Impl::bind_pass(const View& view, const Vpl& vpl,
                                          std::vector<glm::vec2>& last_offsets) {
  const int set = interleave_sets.set_of(vpl.path);
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
  if (batched && batched->matches(options.batch, resolution, ortho)) return;
  batched = gl::BatchedPasses::make(
      api, scene, options.clamp, options.batch, resolution, ortho, drawn_lod(),
      lists_unsure_pixels(options), &lod, context.get(), shadow_helpers(),
      rays_allowed() ? options.visibility_tracer : nullptr, options.visibility == Visibility::Rays);
  if (batched && planes_pending(options)) batched->ask_planes([this] { settle_planes(); });
}

void RasterRenderer::Impl::settle_planes() {
  if (!planes_pending(options)) return;
  const ShadowPlanes chosen = options.choose_planes();
  options.shadow_lod.planes = chosen == ShadowPlanes::Off ? ShadowPlanes::Off : ShadowPlanes::On;
  const bool on = options.shadow_lod.planes == ShadowPlanes::On;
  vpl_shader.set_planes(on);
  if (batched) batched->set_planes(on);
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
    gbuffer = std::make_unique<gl::GBuffer>(api, view.width, view.height, target->depth(),
                                            gpu.features().glossy);
  shadow_res = resolution;
  if (options.interleave > 1 && !interleaved)
    interleaved = std::make_unique<gl::Interleaved>(api, options.interleave, *gbuffer,
                                                    options.edge_pixels == EdgePixelMode::Listed,
                                                    options.edge_pixels == EdgePixelMode::Shaded);
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
  const JitterCells<const Vpl*> cells = jitter_cells(jitter != nullptr, std::move(many),
                                                     [](const Vpl* v) -> const Vpl& { return *v; });
  std::array<bool, kJitterStrata + 1> used{};
  for (std::size_t s = 0; s < cells.size(); ++s) used[s] = !cells[s].empty();
  std::size_t drawn = 0, before = 0;
  by_cell(view, used, [&](const gl::DeferredTarget& into, std::size_t s) {
    const std::vector<const Vpl*>& some = cells[s];
    bool go = true;
    drawn += batched->draw(
        some, [&](const Vpl& v) { return interleave_sets.set_of(v.path); }, into, gpu, timer,
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

void RasterRenderer::Impl::by_cell(const View& view,
                                   const std::array<bool, kJitterStrata + 1>& used,
                                   const ShadeInto& shade) {
  for (std::size_t s = 0; s < used.size(); ++s) {
    if (!used[s]) continue;
    if (s == kJitterStrata) { // the pixel centre: the image's G-buffer
      if (!shade(deferred_target(), s)) return;
      continue;
    }
    const gl::GBuffer& cell = jitter->stratum_gbuffer(camera, view, static_cast<int>(s), gpu);
    if (!shade({&cell, interleaved.get(), [t = target.get()] { t->bind(); }}, s)) return;
  }
}

std::size_t RasterRenderer::Impl::vpl_passes(const View& view, const std::vector<const Vpl*>& vpls,
                                             const ShadowFor& shadow_for, float texel_angle,
                                             gl::PassTimer* timer, const Progress& progress) {
  if (!vpls.empty()) {
    settle_planes();
    ensure_tile_depths(view);
  }
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
  image_lod = nullptr;
  if (gbuffer) {
    // The full-resolution G-buffer; its depth is the target's.
    if (camera_lod_wanted(scene, options)) image_lod = camera_lod.prepared(view);
    camera.gbuffer(*gbuffer, vp, gl::eye_uniform(view), gpu, image_lod);
    if (jitter) jitter->average_albedo(camera, view, gpu);
    if (interleaved) interleaved->find_edges();
    if (interleaved && batched) interleaved->mark_receivers(); // the deferred passes read it
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

Image RasterRenderer::Impl::finish_image(const View& view, Clock::time_point t0, std::size_t passes,
                                         gl::PassTimer* timer, RasterTimings* timings) {
  // The unsure light is the batched passes' alone: listed only when every VPL went through them.
  const bool listed = lists_unsure_pixels(options);
  if (listed && single_passes == 0) interleaved->find_unsure();
  target->bind();
  // The edge pixels hold every VPL only when all went through the batched passes.
  if (interleaved) interleaved->resolve(interleave_sets.scales(), single_passes == 0);
  if (jitter) {
    jitter->emitters(camera, view, scene, gpu, background.get());
  } else {
    camera.emitters(view.projection * view.view, scene, gpu, 1.0f, image_lod);
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
    const gl::EdgePixels* edges = interleaved ? interleaved->edges() : nullptr;
    const bool kept = options.edge_pixels == EdgePixelMode::Listed || single_passes == 0;
    timings->edge_pixels = edges && kept ? edges->edge_count() : 0;
    timings->unsure_pixels = edges && listed ? edges->count() - edges->edge_count() : 0;
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
  if (options.shadow_helpers < -1 || options.shadow_helpers > 8)
    throw Error("", "--shadow-helpers", "must be between 0 and 8, or auto");
  if (options.visibility == Visibility::Rays)
    if (const char* why = rays_refused(options))
      throw Error("", "--visibility", std::string("rays do not take ") + why);
}

bool expects_cpu_renderer(GlBackend backend, int device) {
  return gl::expects_cpu_renderer(backend, device);
}

const char* rays_refused(const RasterOptions& o) {
  if (o.batch < 2) return "--batch 1 (the per-VPL passes draw their own shadow maps)";
  if (o.jitter) return "--jitter (each VPL's G-buffer moves)";
  if (o.edge_pixels == EdgePixelMode::Shaded) return "--interleave-edges shaded";
  if (o.camera_lod == CameraLodMode::On)
    return "--camera-lod on (its G-buffer lies off the surfaces the rays start from)";
  return nullptr;
}

RasterRenderer::RasterRenderer(const Scene& scene, const RasterOptions& options) {
  check_raster_options(options);
  if (options.visibility == Visibility::Rays && !options.visibility_tracer)
    throw Error("", "--visibility", "rays need a ray tracer (irad::render gives one)");
  auto start = StageTimes::Clock::now();
  auto context = gl::create_context(options.backend, options.gl_device);
  if (options.gl_messages) context->route_debug_messages(options.gl_messages);
  StageTimes times;
  start = times.lap("gl context", start);
  impl_ = std::make_unique<Impl>(scene, options, std::move(context));
  times.lap("gl upload", start);
  impl_->setup_times = std::move(times);
  impl_->context->release();
}

CacheResult RasterRenderer::hierarchy_cache() const {
  return impl_->lod.cache_result();
}

StageTimes RasterRenderer::hierarchy_beside_times() const {
  return impl_->lod.beside_times();
}

StageTimes RasterRenderer::setup_times() const {
  StageTimes times = impl_->setup_times;
  times.add("", impl_->lod.setup_times());
  times.add("", impl_->camera_lod.setup_times());
  return times;
}

StageTimes RasterRenderer::camera_hierarchy_beside_times() const {
  return impl_->camera_lod.source().beside_times();
}

CacheResult RasterRenderer::camera_hierarchy_cache() const {
  return impl_->camera_lod.source().cache_result();
}

bool camera_lod_wanted(const Scene& scene, const RasterOptions& options) {
  return options.camera_lod == CameraLodMode::On && !options.jitter && !scene.animation;
}

ClusterOptions camera_cluster_options() {
  ClusterOptions o;
  o.camera = true;
  return o;
}

// The GL objects are deleted in their own context.
RasterRenderer::~RasterRenderer() {
  if (impl_) gl::make_current_for_teardown(*impl_->context);
}

void RasterRenderer::scene_changed() {
  const gl::CurrentScope current(*impl_->context);
  impl_->gpu.update_vertices();
}

std::vector<glm::ivec2> RasterRenderer::edge_pixels() const {
  const gl::EdgePixels* edges = impl_->interleaved ? impl_->interleaved->edges() : nullptr;
  if (!edges) return {};
  std::vector<glm::ivec2> pixels = edges->pixels();
  const int height = impl_->target->height(); // GL's row 0 is the image's bottom
  for (glm::ivec2& p : pixels) p.y = height - 1 - p.y;
  return pixels;
}

bool RasterRenderer::lists_edge_pixels() const {
  return impl_->options.edge_pixels == EdgePixelMode::Listed;
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
  // N: the walk's paths (or past them, for a hand-made set whose VPLs name more).
  std::uint32_t paths = vpls.paths;
  for (const Vpl& v : vpls.vpls) paths = std::max(paths, v.path + 1);
  im.deal_paths(paths);
  std::optional<gl::PassTimer> timer;
  if (im.options.gpu_timers) timer.emplace(im.api);
  // The glossy VPLs' lobes, for this image's passes only.
  im.vpl_shader.set_eye(gl::eye_uniform(view));
  im.vpl_shader.set_lobes(&vpls.lobes);
  im.vpl_shader.set_traced_roughness(im.options.traced_roughness);
  if (im.batched) {
    im.batched->set_vpls(&vpls);
    im.batched->set_lobes(&vpls.lobes);
    im.batched->set_traced_roughness(im.options.traced_roughness);
  }
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
  im.vpl_shader.set_lobes(nullptr);
  im.vpl_shader.set_traced_roughness(0.0f);
  if (im.batched) {
    im.batched->set_vpls(nullptr);
    im.batched->set_lobes(nullptr);
    im.batched->set_traced_roughness(0.0f);
  }
  Image image = im.finish_image(view, t0, passes, timer ? &*timer : nullptr, timings);
  if (timings) {
    if (im.image_lod) timings->camera_triangles = im.image_lod->triangles();
    timings->gpu_scene_bytes = im.gpu.bytes();
    timings->gpu_shadow_pages_bytes = im.lod.gpu_bytes();
    timings->gpu_camera_pages_bytes = im.camera_lod.gpu_bytes();
    const gl::ShadowLod::LateLevels late = im.lod.late_levels();
    timings->shadow_levels_built = late.nodes;
    timings->shadow_levels_seconds = late.seconds;
    timings->shadow_levels_read = im.lod.late_levels_read();
  }
  if (timings && im.batched) {
    timings->shadow_triangles = im.batched->shadow_triangles();
    timings->shadow_helpers = im.batched->helpers();
    timings->ray_visibility = im.batched->rays();
    timings->visibility_seconds = im.batched->visibility_seconds();
  }
  return image;
}

} // namespace irad
