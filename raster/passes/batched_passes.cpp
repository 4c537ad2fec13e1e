#include "raster/passes/batched_passes.h"

#include <algorithm>

namespace irad::gl {

namespace {

bool carries_light(const Vpl& v) {
  return v.intensity.x > 0.0f || v.intensity.y > 0.0f || v.intensity.z > 0.0f;
}

} // namespace

std::unique_ptr<BatchedPasses> BatchedPasses::make(const GladGLContext& api, const Scene& scene,
                                                   float clamp, int batch, int resolution,
                                                   const ShadowLodOptions& lod) {
  if (batch < 2) return nullptr;
  const int b = ShadowAtlas::capacity(api, resolution, batch);
  if (b < 2 || !BatchedShader::fits(api, b)) return nullptr;
  return std::make_unique<BatchedPasses>(api, scene, clamp, batch, b, resolution, lod);
}

BatchedPasses::BatchedPasses(const GladGLContext& api, const Scene& scene, float clamp,
                             int requested, int batch, int resolution,
                             const ShadowLodOptions& lod)
    : requested_(requested),
      atlas_(api, resolution, batch, batch, scene.bounds, MaterialFeatures::of(scene), lod),
      shader_(api, scene, clamp, batch) {}

void BatchedPasses::flush(const View& view, std::vector<Entry>& batch,
                          const Interleaved* interleaved, const Target& target, const GpuScene& gpu,
                          PassTimer* timer) {
  std::stable_sort(batch.begin(), batch.end(),
                   [](const Entry& a, const Entry& b) { return a.set < b.set; });
  vpls_.clear();
  for (const Entry& e : batch) vpls_.push_back(e.vpl);
  const int n = static_cast<int>(batch.size());
  if (timer) timer->begin(PassTimer::Shadow);
  atlas_.render(vpls_.data(), n, gpu, frames_, fars_, blocks_);
  if (timer) timer->end();
  if (timer) timer->begin(PassTimer::Shading);
  shader_.upload(vpls_.data(), n, frames_, fars_, blocks_);
  for (int first = 0; first < n;) {
    const int set = batch[static_cast<std::size_t>(first)].set;
    int end = first + 1;
    while (end < n && batch[static_cast<std::size_t>(end)].set == set) ++end;
    // The view-projection and viewport of the per-VPL pass of this set (and of its depth).
    glm::mat4 vp = view.projection * view.view;
    if (interleaved) {
      interleaved->bind_tile(set);
      vp = interleaved->tile_projection(set, view.projection) * view.view;
    } else {
      target.bind();
    }
    shader_.draw(first, end - first, vp, atlas_, !interleaved, gpu);
    first = end;
  }
  if (timer) timer->end();
  batch.clear();
}

std::size_t BatchedPasses::draw(const View& view, const std::vector<const Vpl*>& vpls,
                                const std::function<int(const Vpl&)>& set_of,
                                const Interleaved* interleaved, const Target& target,
                                const GpuScene& gpu, PassTimer* timer,
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
        flush(view, batch, interleaved, target, gpu, timer);
        blocks = 0;
      }
      batch.push_back({&vpl, interleaved ? set_of(vpl) : 0});
      blocks += need;
    }
    if (static_cast<int>(batch.size()) == atlas_.batch() || k + 1 == vpls.size()) {
      drawn += batch.size();
      flush(view, batch, interleaved, target, gpu, timer);
      blocks = 0;
      if (after && !after(k + 1)) break;
    }
  }
  return drawn;
}

} // namespace irad::gl
