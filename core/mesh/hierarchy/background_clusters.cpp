#include "core/mesh/hierarchy/background_clusters.h"

namespace irad {

BackgroundClusters::BackgroundClusters(const Scene& scene, const ClusterOptions& options,
                                       std::filesystem::path cache, const BackgroundClusters* after)
    : scene_(&scene), options_(options), cache_(std::move(cache)), future_(hierarchy_.get_future()),
      built_future_(built_.get_future().share()), building_future_(building_.get_future().share()) {
  std::shared_future<void> first = after ? after->built_future_ : std::shared_future<void>{};
  done_ = std::async(std::launch::async, [this, first] {
    if (first.valid()) first.wait();
    PendingCacheWrite write;
    bool told = false; // whether building_ is set
    const auto tell = [&](bool building) {
      if (!told) building_.set_value(building);
      told = true;
    };
    try {
      hierarchy_.set_value(cached_mesh_clusters(*scene_, options_, cache_, &times_, &result_,
                                                &write, [&] { tell(true); }));
    } catch (...) {
      hierarchy_.set_exception(std::current_exception());
      tell(false);
      built_.set_value();
      return;
    }
    tell(false);
    built_.set_value();
    write.run(&times_, &result_);
  });
}

void BackgroundClusters::wait_for_build() const {
  if (building_future_.get()) done_.wait();
}

BackgroundClusters::~BackgroundClusters() {
  if (done_.valid()) done_.wait();
}

bool BackgroundClusters::builds(const Scene& scene, const ClusterOptions& options,
                                const std::filesystem::path& cache) const {
  return future_.valid() && &scene == scene_ && cache == cache_ &&
         options.leaf_triangles == options_.leaf_triangles &&
         options.simplify == options_.simplify && options.max_levels == options_.max_levels &&
         options.camera == options_.camera && options.defer_levels == options_.defer_levels;
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

ClusterSource::ClusterSource(std::string name, std::filesystem::path cache,
                             std::shared_ptr<BackgroundClusters> prebuilt)
    : name_(std::move(name)), cache_(std::move(cache)), prebuilt_(std::move(prebuilt)) {}

MeshClusters ClusterSource::get(const Scene& scene, const ClusterOptions& wanted,
                                StageTimes& times) {
  MeshClusters clusters;
  if (prebuilt_ && prebuilt_->builds(scene, wanted, cache_)) {
    const auto start = StageTimes::Clock::now();
    clusters = prebuilt_->take();
    times.lap(name_ + "wait", start);
    taken_ = prebuilt_;
  } else {
    StageTimes build;
    clusters = cached_mesh_clusters(scene, wanted, cache_, &build, &cache_result_);
    times.add(name_, build);
  }
  prebuilt_.reset();
  return clusters;
}

StageTimes ClusterSource::beside_times() const {
  StageTimes out;
  if (taken_) out.add(name_, taken_->times());
  return out;
}

CacheResult ClusterSource::cache_result() const {
  return taken_ ? taken_->cache_result() : cache_result_;
}

} // namespace irad
