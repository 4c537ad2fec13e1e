#include "raster/passes/batched_passes.h"

#include <algorithm>

namespace irad::gl {

namespace {

bool carries_light(const Vpl& v) {
  return v.intensity.x > 0.0f || v.intensity.y > 0.0f || v.intensity.z > 0.0f;
}

} // namespace

std::unique_ptr<BatchedPasses> BatchedPasses::make(const GladGLContext& api, const Scene& scene,
                                                   float clamp, int batch, int resolution) {
  if (batch < 2) return nullptr;
  const int b = ShadowAtlas::capacity(api, resolution, batch);
  if (b < 2 || DeferredShader::capacity(api, b) < b) return nullptr;
  return std::make_unique<BatchedPasses>(api, scene, clamp, batch, b, resolution);
}

BatchedPasses::BatchedPasses(const GladGLContext& api, const Scene& scene, float clamp,
                             int requested, int batch, int resolution)
    : requested_(requested),
      atlas_(api, resolution, batch, batch, scene.bounds, MaterialFeatures::of(scene)),
      shader_(api, scene, clamp, DeferredShader::capacity(api, std::max(batch, kShadingBatch))) {}

void BatchedPasses::flush(std::vector<Entry>& batch, const DeferredTarget& into,
                          const GpuScene& gpu, PassTimer* timer) {
  std::stable_sort(batch.begin(), batch.end(),
                   [](const Entry& a, const Entry& b) { return a.set < b.set; });
  vpls_.clear();
  for (const Entry& e : batch) vpls_.push_back(e.vpl);
  const int n = static_cast<int>(batch.size());
  if (timer) timer->begin(PassTimer::Shadow);
  atlas_.render(vpls_.data(), n, gpu, frames_, fars_, blocks_);
  if (timer) timer->end();
  if (timer) timer->begin(PassTimer::Shading);
  shaded_.clear();
  for (int s = 0; s < n; ++s) {
    const auto u = static_cast<std::size_t>(s);
    shaded_.push_back({vpls_[u], frames_[u], fars_[u], blocks_[u], batch[u].set});
  }
  shade_some(shaded_.data(), n, {atlas_.texture(), atlas_.resolution()}, into);
  if (timer) timer->end();
  batch.clear();
}

void BatchedPasses::shade(std::vector<AtlasVpl>& vpls, const ShadowLookup& shadow,
                          const DeferredTarget& into) {
  std::stable_sort(vpls.begin(), vpls.end(),
                   [](const AtlasVpl& a, const AtlasVpl& b) { return a.set < b.set; });
  const int n = static_cast<int>(vpls.size());
  for (int first = 0; first < n; first += shader_.batch())
    shade_some(vpls.data() + first, std::min(shader_.batch(), n - first), shadow, into);
}

void BatchedPasses::shade_some(const AtlasVpl* vpls, int n, const ShadowLookup& shadow,
                               const DeferredTarget& into) {
  vpls_.clear();
  frames_.clear();
  fars_.clear();
  blocks_.clear();
  for (int s = 0; s < n; ++s) {
    vpls_.push_back(vpls[s].vpl);
    frames_.push_back(vpls[s].frame);
    fars_.push_back(vpls[s].far);
    blocks_.push_back(vpls[s].blocks);
  }
  shader_.upload(vpls_.data(), n, frames_, fars_, blocks_);
  for (int first = 0; first < n;) {
    const int set = vpls[first].set;
    int end = first + 1;
    while (end < n && vpls[end].set == set) ++end;
    // The set's tile: its pixel t stands for image pixel k t + (set mod k, set / k), the pixel
    // whose centre the per-VPL pass's tile projection puts there (Interleaved::tile_projection).
    TilePixels pixels;
    if (into.interleaved) {
      into.interleaved->bind_tile(set);
      const int k = into.interleaved->k();
      pixels = {glm::ivec2(into.interleaved->tile(set)), k, glm::ivec2(set % k, set / k)};
    } else {
      into.target->bind();
    }
    shader_.draw(first, end - first, pixels, *into.gbuffer, shadow, !into.interleaved);
    first = end;
  }
}

std::size_t BatchedPasses::draw(const std::vector<const Vpl*>& vpls,
                                const std::function<int(const Vpl&)>& set_of,
                                const DeferredTarget& into, const GpuScene& gpu, PassTimer* timer,
                                const std::function<bool(std::size_t)>& after) {
  std::vector<Entry> batch;
  int blocks = 0;
  std::size_t drawn = 0;
  for (std::size_t k = 0; k < vpls.size(); ++k) {
    const Vpl& vpl = *vpls[k];
    if (carries_light(vpl)) {
      const int need = ShadowAtlas::blocks_for(vpl);
      if (blocks + need > atlas_.blocks()) { // a whole cube where only a hemisphere fits
        drawn += batch.size();
        flush(batch, into, gpu, timer);
        blocks = 0;
      }
      batch.push_back({&vpl, into.interleaved ? set_of(vpl) : 0});
      blocks += need;
    }
    if (static_cast<int>(batch.size()) == atlas_.batch() || k + 1 == vpls.size()) {
      drawn += batch.size();
      flush(batch, into, gpu, timer);
      blocks = 0;
      if (after && !after(k + 1)) break;
    }
  }
  return drawn;
}

} // namespace irad::gl
