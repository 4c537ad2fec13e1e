#include "raster/shadow/lod_provider.h"

#include "core/util/freed_memory.h"

namespace irad::gl {

LodProvider::LodProvider(const GladGLContext& api, const GpuScene& gpu,
                         const ShadowLodOptions& options, std::filesystem::path cache,
                         std::shared_ptr<BackgroundClusters> prebuilt)
    : api_(&api), gpu_(&gpu), options_(options), cache_(std::move(cache)),
      prebuilt_(std::move(prebuilt)) {}

const ShadowLod* LodProvider::get() {
  if (options_.mode == ShadowLodMode::Off || gpu_->scene().animation) return nullptr;
  if (!lod_) {
    // Cull draws the scene's own triangles (the same image as Off), On also their reductions.
    const bool on = options_.mode == ShadowLodMode::On;
    const ClusterOptions wanted{0, on};
    auto start = StageTimes::Clock::now();
    MeshClusters clusters;
    if (prebuilt_ && prebuilt_->builds(gpu_->scene(), wanted, cache_)) {
      clusters = prebuilt_->take();
      start = times_.lap("hierarchy wait", start);
      taken_ = prebuilt_; // its cache file may still be written
    } else {
      StageTimes build;
      clusters = cached_mesh_clusters(gpu_->scene(), wanted, cache_, &build, &cache_result_);
      times_.add("hierarchy ", build);
      start = StageTimes::Clock::now();
    }
    prebuilt_.reset(); // taken, or a build of other options: not asked again
    lod_ = std::make_unique<ShadowLod>(*api_, *gpu_, std::move(clusters), on);
    release_freed_memory(); // the build's transients
    times_.lap("hierarchy upload", start);
  }
  return lod_.get();
}

StageTimes LodProvider::beside_times() const {
  StageTimes out;
  if (taken_) out.add("hierarchy ", taken_->times());
  return out;
}

CacheResult LodProvider::cache_result() const {
  return taken_ ? taken_->cache_result() : cache_result_;
}

} // namespace irad::gl
