#include "raster/shadow/lod_provider.h"

#include "core/util/freed_memory.h"

namespace irad::gl {

LodProvider::LodProvider(const GladGLContext& api, const GpuScene& gpu,
                         const ShadowLodOptions& options, std::filesystem::path cache,
                         std::shared_ptr<BackgroundClusters> prebuilt)
    : api_(&api), gpu_(&gpu), options_(options),
      source_("hierarchy ", std::move(cache), std::move(prebuilt)) {}

const ShadowLod* LodProvider::get() {
  if (options_.mode == ShadowLodMode::Off || gpu_->scene().animation) return nullptr;
  if (!lod_) {
    // Cull draws the scene's own triangles (the same image as Off), On also their reductions.
    const bool on = options_.mode == ShadowLodMode::On;
    MeshClusters clusters = source_.get(gpu_->scene(), ClusterOptions{0, on}, times_);
    const auto start = StageTimes::Clock::now();
    lod_ = std::make_unique<ShadowLod>(*api_, *gpu_, std::move(clusters), on);
    release_freed_memory(); // the build's transients
    times_.lap("hierarchy upload", start);
  }
  return lod_.get();
}

} // namespace irad::gl
