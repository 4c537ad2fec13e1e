#include "raster/shadow/lod_provider.h"

#include "core/mesh/hierarchy/late_levels_file.h"
#include "core/util/freed_memory.h"

namespace irad::gl {

LodProvider::LodProvider(const GladGLContext& api, const GpuScene& gpu,
                         const ShadowLodOptions& options, std::filesystem::path cache,
                         std::shared_ptr<BackgroundClusters> prebuilt)
    : api_(&api), gpu_(&gpu), options_(options),
      source_("hierarchy ", std::move(cache), std::move(prebuilt)) {}

LodProvider::~LodProvider() {
  keep_late_levels();
}

void LodProvider::keep_late_levels() noexcept {
  if (!lod_ || lod_->late_levels().nodes == 0) return; // nothing built since the cache read
  const CacheResult cache = source_.cache_result();
  if (cache.file.empty() || cache.outcome == CacheOutcome::Unwritable) return;
  std::string why; // a file not written: its levels are built again where needed
  write_late_levels(cache.file, cache.key, lod_->clusters(), why);
}

const ShadowLod* LodProvider::get() {
  if (options_.mode == ShadowLodMode::Off || gpu_->scene().animation) return nullptr;
  if (!lod_) {
    const ClusterOptions o = shadow_cluster_options(options_);
    MeshClusters clusters = source_.get(gpu_->scene(), o, times_);
    late_read_ = clusters.late_nodes.size();
    const auto start = StageTimes::Clock::now();
    lod_ = std::make_unique<ShadowLod>(*api_, *gpu_, std::move(clusters), o.simplify);
    release_freed_memory(); // the build's transients
    times_.lap("hierarchy upload", start);
  }
  return lod_.get();
}

} // namespace irad::gl
