#include "raster/shadow/lod_provider.h"

namespace irad::gl {

LodProvider::LodProvider(const GladGLContext& api, const GpuScene& gpu,
                         const ShadowLodOptions& options, std::filesystem::path cache)
    : api_(&api), gpu_(&gpu), options_(options), cache_(std::move(cache)) {}

const ShadowLod* LodProvider::get() {
  if (options_.mode == ShadowLodMode::Off || gpu_->scene().animation) return nullptr;
  if (!lod_) {
    // Cull draws the scene's own triangles (the same image as Off), On also their reductions.
    const bool on = options_.mode == ShadowLodMode::On;
    StageTimes build;
    MeshClusters clusters =
        cached_mesh_clusters(gpu_->scene(), {0, on}, cache_, &build, &cache_result_);
    times_.add("hierarchy ", build);
    const auto start = StageTimes::Clock::now();
    lod_ = std::make_unique<ShadowLod>(*api_, *gpu_, std::move(clusters), on);
    times_.lap("hierarchy upload", start);
  }
  return lod_.get();
}

} // namespace irad::gl
