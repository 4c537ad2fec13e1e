#include "raster/passes/batched_passes.h"

#include "core/util/error.h"

#include <algorithm>

namespace irad::gl {

namespace {

// The pixels one VPL shades: its interleaved set's tile, or the whole image.
glm::ivec2 shaded_tile(const DeferredTarget& into) {
  if (!into.interleaved) return {into.gbuffer->width(), into.gbuffer->height()};
  const glm::ivec4 tile = into.interleaved->tile(0);
  return {tile.z, tile.w};
}

} // namespace

std::unique_ptr<BatchedPasses>
BatchedPasses::make(const GladGLContext& api, const Scene& scene, float clamp, int batch,
                    int resolution, int ortho_resolution, const ShadowLodOptions& lod, bool unsure,
                    LodProvider* shared, Context* context, int helpers, VisibilityTracer rays,
                    bool rays_now) {
  if (batch < 2) return nullptr;
  const int b = ShadowAtlas::capacity(api, resolution, batch);
  if (b < 2 || DeferredShader::capacity(api, b, !scene.all_lambertian()) < b) return nullptr;
  const int tiles = ortho_resolution > 0
                        ? OrthoAtlas::capacity(api, ortho_resolution, std::min(b, kOrthoTiles))
                        : 0;
  return std::make_unique<BatchedPasses>(api, scene, clamp, batch, b, resolution, tiles,
                                         tiles > 0 ? ortho_resolution : 0, lod, unsure, shared,
                                         context, helpers, std::move(rays), rays_now);
}

BatchedPasses::BatchedPasses(const GladGLContext& api, const Scene& scene, float clamp,
                             int requested, int batch, int resolution, int ortho_tiles,
                             int ortho_resolution, const ShadowLodOptions& lod, bool unsure,
                             LodProvider* shared, Context* context, int helpers,
                             VisibilityTracer rays, bool rays_now)
    : requested_(requested),
      atlas_(api, resolution, batch, batch, scene.bounds, MaterialFeatures::of(scene), lod, shared),
      ortho_(ortho_tiles > 0
                 ? std::make_unique<OrthoAtlas>(api, ortho_resolution, ortho_tiles, scene.bounds,
                                                MaterialFeatures::of(scene))
                 : nullptr),
      shader_(
          api, scene, clamp,
          DeferredShader::capacity(api, std::max(batch, kShadingBatch), !scene.all_lambertian()),
          lod.planes != ShadowPlanes::Off, unsure),
      context_(context), max_helpers_(context && !rays_now ? helpers : 0),
      rays_(rays ? std::make_unique<RayVisibility>(api, std::move(rays)) : nullptr),
      rays_now_(rays_ && rays_now), rays_on_(rays_now_) {
  if (rays_now_) atlas_.release_atlases(); // never drawn
}

void BatchedPasses::draw_ortho(const std::vector<std::size_t>& directional, const GpuScene& gpu) {
  // One map per direction: a directional light's VPLs (or a sun's) share theirs.
  directions_.clear();
  std::vector<int> tile(directional.size());
  for (std::size_t i = 0; i < directional.size(); ++i) {
    const glm::vec3& d = shaded_[directional[i]].vpl->normal;
    const auto same = std::find(directions_.begin(), directions_.end(), d);
    tile[i] = static_cast<int>(same - directions_.begin());
    if (same == directions_.end()) directions_.push_back(d);
  }
  ortho_->render(directions_.data(), static_cast<int>(directions_.size()), gpu, lookups_, origins_);
  for (std::size_t i = 0; i < directional.size(); ++i) {
    AtlasVpl& a = shaded_[directional[i]];
    const auto t = static_cast<std::size_t>(tile[i]);
    a.lookup = lookups_[t];
    a.blocks = glm::ivec4(origins_[t], 0, 0);
    a.half_width = ortho_->half_width();
    a.texel = ortho_->texel();
  }
}

void BatchedPasses::gather(const std::vector<Entry>& batch) {
  shaded_.clear();
  vpls_.clear();
  cubes_.clear();
  directional_.clear();
  for (const Entry& e : batch) {
    (e.vpl->kind == VplKind::Directional ? directional_ : cubes_).push_back(shaded_.size());
    AtlasVpl a{e.vpl, glm::mat3(1.0f), 1.0f, glm::ivec4(0), e.set};
    a.lobe = lobe_of(*e.vpl);
    shaded_.push_back(a);
  }
  for (std::size_t i : cubes_) vpls_.push_back(shaded_[i].vpl);
}

void BatchedPasses::flush(const std::vector<Entry>& batch, const DeferredTarget& into,
                          const GpuScene& gpu, PassTimer* timer) {
  gather(batch);
  if (rays_on_) { // no maps: the shading reads the rays' answers
    complete(atlas_.texture(), atlas_.gradient_texture(), frames_, fars_, blocks_, into, gpu,
             timer);
    return;
  }
  if (timer) timer->begin(PassTimer::Shadow);
  if (!vpls_.empty()) {
    atlas_.render(vpls_.data(), static_cast<int>(vpls_.size()), gpu, frames_, fars_, blocks_);
    shadow_triangles_ += atlas_.cluster_triangles();
  }
  if (timer) timer->end();
  complete(atlas_.texture(), atlas_.gradient_texture(), frames_, fars_, blocks_, into, gpu, timer);
}

void BatchedPasses::complete(GLuint texture, GLuint gradient, const std::vector<glm::mat3>& frames,
                             const std::vector<float>& fars, const std::vector<glm::ivec4>& blocks,
                             const DeferredTarget& into, const GpuScene& gpu, PassTimer* timer) {
  if (!directional_.empty() && !rays_on_) {
    if (timer) timer->begin(PassTimer::Shadow);
    draw_ortho(directional_, gpu);
    if (timer) timer->end();
  }
  for (std::size_t c = 0; c < cubes_.size() && !rays_on_; ++c) {
    AtlasVpl& a = shaded_[cubes_[c]];
    a.frame = frames[c];
    a.far = fars[c];
    a.blocks = blocks[c];
  }
  if (cubes_.empty()) { // no cube is read, but the shading binds an atlas and its gradients
    texture = atlas_.texture();
    gradient = atlas_.gradient_texture();
  }
  if (timer) timer->begin(PassTimer::Shading);
  ShadowLookup lookup{texture, atlas_.resolution()};
  if (ortho_) lookup = {texture, atlas_.resolution(), ortho_->texture(), ortho_->resolution()};
  lookup.gradient = gradient;
  shade(shaded_, lookup, into);
  if (timer) timer->end();
}

void BatchedPasses::shade(std::vector<AtlasVpl>& vpls, const ShadowLookup& shadow,
                          const DeferredTarget& into) {
  // By set, and within a set the Lambertian VPLs before the glossy ones (DeferredShader::draw
  // draws each run with its own program).
  std::stable_sort(vpls.begin(), vpls.end(), [](const AtlasVpl& a, const AtlasVpl& b) {
    const bool la = a.lobe != nullptr, lb = b.lobe != nullptr;
    return a.set < b.set || (a.set == b.set && la < lb);
  });
  const int n = static_cast<int>(vpls.size());
  int step = shader_.batch();
  if (rays_on_) { // each VPL's answers take a byte per pixel it shades
    const glm::ivec2 tile = shaded_tile(into);
    const std::size_t bytes = static_cast<std::size_t>(tile.x) * static_cast<std::size_t>(tile.y);
    step = static_cast<int>(std::clamp<std::size_t>(
        kRayAnswerBytes / std::max<std::size_t>(bytes, 1), 1, static_cast<std::size_t>(step)));
  }
  for (int first = 0; first < n; first += step)
    shade_some(vpls.data() + first, std::min(step, n - first), shadow, into);
}

void BatchedPasses::shade_some(const AtlasVpl* vpls, int n, const ShadowLookup& shadow,
                               const DeferredTarget& into) {
  shader_.upload(vpls, n);
  ShadowLookup lookup = shadow;
  if (rays_on_) {
    const int k = into.interleaved ? into.interleaved->k() : 1;
    lookup.visibility = rays_->answer(vpls, n, k, shaded_tile(into));
  }
  for (int first = 0; first < n;) {
    const int set = vpls[first].set;
    int end = first + 1;
    while (end < n && vpls[end].set == set) ++end;
    // The set's tile: its pixel t stands for image pixel k t + (set mod k, set / k), the pixel
    // whose centre the per-VPL pass's tile projection puts there (Interleaved::tile_projection).
    TilePixels pixels;
    if (into.interleaved) {
      into.interleaved->bind_tile(set, into.receivers);
      const int k = into.interleaved->k();
      pixels = {glm::ivec2(into.interleaved->tile(set)), k, glm::ivec2(set % k, set / k), 0,
                into.receivers};
    } else {
      into.bind_image();
    }
    shader_.draw(first, end - first, pixels, *into.gbuffer, lookup, !into.interleaved);
    first = end;
  }
  // The edge pixels: every set's VPLs, unscaled (the sets' sum is the whole estimate whatever
  // their sizes: core/lights/interleave_sets.h).
  const EdgePixels* edges = into.interleaved ? into.interleaved->shaded_edges() : nullptr;
  if (edges == nullptr) return;
  edges->bind_light();
  TilePixels listed;
  listed.list = edges->list();
  shader_.draw(0, n, listed, *into.gbuffer, lookup, false);
}

std::vector<BatchedPasses::Batch>
BatchedPasses::form_batches(const std::vector<const Vpl*>& order, std::size_t first, int size,
                            int atlas_blocks, const std::function<int(const Vpl&)>& set_of,
                            const DeferredTarget& into, std::size_t most) const {
  std::vector<Batch> batches;
  Batch batch;
  int blocks = 0;
  std::vector<glm::vec3> directions; // the batch's distinct directions
  const auto send = [&](std::size_t end) {
    batch.end = end;
    batches.push_back(std::move(batch));
    batch = {};
    blocks = 0;
    directions.clear();
  };
  for (std::size_t k = first; k < order.size() && batches.size() < most; ++k) {
    const Vpl& vpl = *order[k];
    if (vpl.carries_light()) {
      if (vpl.kind == VplKind::Directional) {
        const bool known =
            std::find(directions.begin(), directions.end(), vpl.normal) != directions.end();
        if (!known && static_cast<int>(directions.size()) == ortho_->tiles()) send(k);
        if (!known) directions.push_back(vpl.normal);
      } else {
        const int need = ShadowAtlas::blocks_for(vpl);
        if (blocks + need > atlas_blocks) send(k); // a whole cube where only a hemisphere fits
        blocks += need;
      }
      batch.entries.push_back({&vpl, into.interleaved ? set_of(vpl) : 0});
    }
    const bool apart = k + 1 < order.size() && !ShadowAtlas::same_batch(vpl, *order[k + 1]);
    if (static_cast<int>(batch.entries.size()) == size || k + 1 == order.size() || apart)
      send(k + 1);
  }
  return batches;
}

std::size_t BatchedPasses::drawn_per_vpl(const LodProvider* lod, std::size_t n,
                                         const GpuScene& gpu) const {
  return lod ? atlas_.cluster_triangles() / n : gpu.scene().triangle_count();
}

bool BatchedPasses::rays_pay(const GpuScene& gpu, const DeferredTarget& into) {
  // Surface VPLs at the points the pixels of a kProbeGrid^2 grid see, facing the camera.
  std::vector<Vpl> probes;
  const int w = into.gbuffer->width(), h = into.gbuffer->height();
  for (int gy = 0; gy < kProbeGrid; ++gy)
    for (int gx = 0; gx < kProbeGrid; ++gx) {
      const int x = (2 * gx + 1) * w / (2 * kProbeGrid), y = (2 * gy + 1) * h / (2 * kProbeGrid);
      const auto [position, normal] = into.gbuffer->texel(x, y);
      if (!(position.w > 0.0f)) continue;
      Vpl v;
      v.position = glm::vec3(position);
      v.normal = glm::vec3(normal);
      v.intensity = glm::vec3(1.0f);
      probes.push_back(v);
    }
  if (probes.empty()) return false;
  std::vector<const Vpl*> list;
  for (const Vpl& v : probes) list.push_back(&v);
  const LodProvider* lod = atlas_.prepare_hierarchy(gpu);
  atlas_.render(list.data(), static_cast<int>(list.size()), gpu, frames_, fars_, blocks_);
  const std::size_t per_vpl = drawn_per_vpl(lod, list.size(), gpu);
  const glm::ivec2 tile = shaded_tile(into);
  const auto pixels = static_cast<std::size_t>(tile.x) * static_cast<std::size_t>(tile.y);
  return per_vpl * kPixelsPerTriangle >= pixels;
}

void BatchedPasses::set_planes(bool on) {
  settle_planes_ = nullptr;
  if (!on) return;
  atlas_.enable_planes();
  shader_.set_planes(true);
}

void BatchedPasses::consider_helpers(int n, const GpuScene& gpu) {
  if (helpers_asked_ || max_helpers_ < 1 || n < 1) return;
  helpers_asked_ = true;
  LodProvider* lod = atlas_.prepare_hierarchy(gpu);
  if (drawn_per_vpl(lod, static_cast<std::size_t>(n), gpu) < kHelperTrianglesPerVpl) return;
  ShadowHelpers::AtlasShape shape{atlas_.resolution(),
                                  helper_batch(),
                                  helper_batch(),
                                  gpu.scene().bounds,
                                  MaterialFeatures::of(gpu.scene()),
                                  atlas_.lod_options()};
  if (!lod) shape.lod.mode = ShadowLodMode::Off; // never a hierarchy of their own
  try {
    helpers_ = std::make_unique<ShadowHelpers>(*context_, max_helpers_, shape, lod);
    atlas_.release_atlases(); // the helpers draw every batch from here on
  } catch (const Error&) {
    // A GL that refuses a shared context or a thread's atlas: this context draws them all, as
    // with --shadow-helpers 0 (RasterTimings::shadow_helpers reports 0).
  }
}

std::size_t BatchedPasses::draw_with_helpers(const std::vector<Batch>& batches, std::size_t first,
                                             const DeferredTarget& into, const GpuScene& gpu,
                                             PassTimer* timer,
                                             const std::function<bool(std::size_t)>& after) {
  const int k = helpers_->count();
  // Jobs in batch order; job i is batches[first + i]'s, on helper i mod k. Each helper holds at
  // most kAhead started and not yet shaded (ShadowHelpers::kSlots).
  std::vector<ShadowHelpers::Job> jobs(batches.size() - first);
  // However the loop ends (stopped early, or an error), no helper still writes into `jobs`.
  struct Drain {
    std::vector<ShadowHelpers::Job>& jobs;
    const ShadowHelpers& helpers;
    ~Drain() {
      for (ShadowHelpers::Job& job : jobs) helpers.abandon(job);
    }
  } drain{jobs, *helpers_};
  std::size_t started = 0, drawn = 0;
  bool go = true;
  const auto start_more = [&](std::size_t shaded) {
    const std::size_t ahead = ShadowHelpers::kAhead * static_cast<std::size_t>(k);
    for (; started < jobs.size() && started < shaded + ahead; ++started) {
      gather(batches[first + started].entries);
      if (vpls_.empty()) continue; // directional only: drawn here when shaded
      jobs[started].vpls = vpls_;
      helpers_->start(static_cast<int>(started % static_cast<std::size_t>(k)), jobs[started], gpu,
                      timer != nullptr);
    }
  };
  for (std::size_t i = 0; i < jobs.size() && go; ++i) {
    start_more(i);
    const Batch& b = batches[first + i];
    gather(b.entries);
    const ShadowHelpers::Drawn none;
    const ShadowHelpers::Drawn& d = vpls_.empty() ? none : helpers_->finish(jobs[i]);
    shadow_triangles_ += d.triangles;
    complete(d.texture, d.gradient, d.frames, d.fars, d.blocks, into, gpu, timer);
    drawn += b.entries.size();
    if (after) go = after(b.end);
  }
  if (timer) timer->add(PassTimer::Shadow, helpers_->take_timed_seconds());
  return drawn;
}

std::size_t BatchedPasses::draw(const std::vector<const Vpl*>& vpls,
                                const std::function<int(const Vpl&)>& set_of,
                                const DeferredTarget& into, const GpuScene& gpu, PassTimer* timer,
                                const std::function<bool(std::size_t)>& after) {
  const std::vector<const Vpl*> order = ShadowAtlas::batch_order(vpls);
  shadow_triangles_ = 0;
  if (rays_) {
    rays_on_ = rays_now_ || (!order.empty() && rays_pay(gpu, into));
    if (rays_on_) rays_->read(*into.gbuffer);
  }
  if (!rays_on_ && settle_planes_) {
    const std::function<void()> settle = std::move(settle_planes_);
    settle_planes_ = nullptr;
    settle(); // calls set_planes
  }
  std::size_t drawn = 0, first = 0;
  // Until the helpers are decided, batches of their size drawn here while kHelperBatches more
  // would follow: what one draws decides.
  while (!rays_on_ && !helpers_asked_ && max_helpers_ > 0 &&
         order.size() - first >= (1 + kHelperBatches) * static_cast<std::size_t>(helper_batch())) {
    const std::vector<Batch> probe =
        form_batches(order, first, helper_batch(), helper_batch(), set_of, into, 1);
    flush(probe[0].entries, into, gpu, timer);
    drawn += probe[0].entries.size();
    first = probe[0].end;
    if (after && !after(first)) return drawn;
    consider_helpers(static_cast<int>(vpls_.size()), gpu);
  }
  if (helpers_)
    return drawn + draw_with_helpers(
                       form_batches(order, first, helper_batch(), helper_batch(), set_of, into), 0,
                       into, gpu, timer, after);
  for (const Batch& b : form_batches(order, first, atlas_.batch(), atlas_.blocks(), set_of, into)) {
    flush(b.entries, into, gpu, timer);
    drawn += b.entries.size();
    if (after && !after(b.end)) break;
  }
  return drawn;
}

} // namespace irad::gl
