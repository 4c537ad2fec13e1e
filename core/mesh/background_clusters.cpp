#include "core/mesh/background_clusters.h"

namespace irad {

BackgroundClusters::BackgroundClusters(const Scene& scene, const ClusterOptions& options,
                                       std::filesystem::path cache)
    : scene_(&scene), options_(options), cache_(std::move(cache)),
      future_(hierarchy_.get_future()) {
  done_ = std::async(std::launch::async, [this] {
    PendingCacheWrite write;
    try {
      hierarchy_.set_value(
          cached_mesh_clusters(*scene_, options_, cache_, &times_, &result_, &write));
    } catch (...) {
      hierarchy_.set_exception(std::current_exception());
      return;
    }
    write.run(&times_, &result_);
  });
}

BackgroundClusters::~BackgroundClusters() {
  if (done_.valid()) done_.wait();
}

bool BackgroundClusters::builds(const Scene& scene, const ClusterOptions& options,
                                const std::filesystem::path& cache) const {
  return future_.valid() && &scene == scene_ && cache == cache_ &&
         options.leaf_triangles == options_.leaf_triangles &&
         options.simplify == options_.simplify && options.max_levels == options_.max_levels;
}

MeshClusters BackgroundClusters::take() {
  return future_.get(); // leaves future_ invalid: taken
}

const StageTimes& BackgroundClusters::times() const {
  done_.wait();
  return times_;
}

const CacheResult& BackgroundClusters::cache_result() const {
  done_.wait();
  return result_;
}

} // namespace irad
