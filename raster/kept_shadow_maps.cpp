// The shadow maps kept per light path (RasterRenderer::cache_path, render_cached): the cached
// walkthrough shades every kept VPL from a moving camera without redrawing a shadow map.
#include "raster/raster_renderer_impl.h"

namespace irad {

std::size_t RasterRenderer::Impl::shade_kept(const View& view) {
  const bool jittered = jitter != nullptr;
  // Each page's VPLs and the directional ones by the G-buffer they read.
  std::vector<gl::ShadowCache::Page> pages = shadow_cache->pages();
  std::vector<JitterCells<gl::AtlasVpl>> page_cells;
  for (gl::ShadowCache::Page& page : pages) {
    for (gl::AtlasVpl& v : page.vpls) v.set = interleave_sets.set_of(v.vpl->path);
    page_cells.push_back(jitter_cells(jittered, std::move(page.vpls),
                                      [](const gl::AtlasVpl& v) -> const Vpl& { return *v.vpl; }));
  }
  std::vector<const Vpl*> directional_vpls;
  for (const CachedPath& p : cache)
    for (const Vpl& v : p.directional) directional_vpls.push_back(&v);
  const JitterCells<const Vpl*> directional_cells = jitter_cells(
      jittered, std::move(directional_vpls), [](const Vpl* v) -> const Vpl& { return *v; });
  std::array<bool, kJitterStrata + 1> used{};
  for (std::size_t s = 0; s < used.size(); ++s) {
    used[s] = !directional_cells[s].empty();
    for (const JitterCells<gl::AtlasVpl>& cells : page_cells)
      used[s] = used[s] || !cells[s].empty();
  }
  std::size_t passes = 0;
  by_cell(view, used, [&](const gl::DeferredTarget& into, std::size_t s) {
    for (std::size_t p = 0; p < pages.size(); ++p) {
      batched->shade(page_cells[p][s], pages[p].lookup, into);
      passes += page_cells[p][s].size();
    }
    passes += batched->draw(directional_cells[s],
                            [&](const Vpl& v) { return interleave_sets.set_of(v.path); }, into, gpu,
                            nullptr, {});
    return true;
  });
  return passes;
}

void RasterRenderer::cache_path(std::uint32_t slot, const std::vector<Vpl>& vpls, int width,
                                int height, const std::vector<VplLobe>& lobes) {
  Impl& im = *impl_;
  const gl::CurrentScope current(*im.context);
  im.settle_planes(); // the kept maps are drawn to shade
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
  im.cached_paths = std::max(im.cached_paths, slot + 1);
  for (const Vpl& v : vpls) im.cached_paths = std::max(im.cached_paths, v.path + 1);
  Impl::CachedPath& path = im.cache[slot];
  // The slot's cubes are drawn over again: no texture allocation per frame once the ring is full.
  std::vector<gl::Texture> spare;
  for (gl::Texture& c : path.cubes)
    if (c.get() != 0) spare.push_back(std::move(c));
  path = {};
  path.lobes = lobes;
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
  if (im.shadow_cache) im.shadow_cache->store(slot, in_atlas, im.gpu, lobes);
  im.context->check("cached shadow maps");
}

Image RasterRenderer::render_cached(const View& view, RasterTimings* timings) {
  Impl& im = *impl_;
  const auto t0 = Clock::now();
  const gl::CurrentScope current(*im.context);
  im.begin_image(view);
  im.deal_paths(im.cached_paths); // the ring's paths
  std::size_t passes = 0;
  if (im.shadow_cache && im.batched) passes += im.shade_kept(view);
  // The VPLs kept as cubes, their lobes gathered into one list (each path's indices moved by the
  // lobes of the paths before it).
  std::vector<Vpl> vpls;
  std::vector<VplLobe> lobes;
  std::vector<std::pair<GLuint, glm::mat3>> maps;
  for (const Impl::CachedPath& p : im.cache) {
    for (std::size_t i = 0; i < p.vpls.size(); ++i) {
      vpls.push_back(p.vpls[i]);
      if (vpls.back().lobe >= 0) vpls.back().lobe += static_cast<std::int32_t>(lobes.size());
      maps.emplace_back(p.cubes[i].get(), p.frames[i]);
    }
    lobes.insert(lobes.end(), p.lobes.begin(), p.lobes.end());
  }
  std::vector<const Vpl*> list;
  for (const Vpl& v : vpls) list.push_back(&v);
  const auto kept = [&](std::size_t k, glm::mat3& frame) {
    if (list[k]->kind == VplKind::Directional) im.directional_shadow(*list[k]);
    frame = maps[k].second;
    return maps[k].first;
  };
  const float texel = im.cache_shadow ? im.cache_shadow->texel_angle() : 1.0f;
  im.vpl_shader.set_eye(gl::eye_uniform(view));
  im.vpl_shader.set_lobes(&lobes);
  passes += im.vpl_passes(view, list, kept, texel, nullptr, {});
  im.vpl_shader.set_lobes(nullptr);
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
