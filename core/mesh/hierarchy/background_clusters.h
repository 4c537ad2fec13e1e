#pragma once
// The shadow hierarchy (core/mesh/hierarchy/mesh_clusters.h, through its cache:
// core/mesh/hierarchy/cluster_cache.h) built on a thread of its own from the moment a render knows
// it will draw from it: its stages that run on one core (the weld, the planar reduction, the tree's
// top splits, the cache file's checksum) then overlap the ray-tracing structure, the walk, the
// clustering and the GL set-up, instead of following them while the other cores wait. The raster
// takes the result where it would have built it (raster/shadow/lod_provider.h; the camera's
// hierarchy, raster/passes/camera_lod.h, through ClusterSource likewise) and waits only for what is
// left.
//
// The same hierarchy as a build in place, bit for bit (the build's result does not depend on its
// threads). An exception of the build reaches the caller of take(); one never taken is dropped.
// A build is handed on before its cache file is written: the thread writes it while the
// hierarchy is in use (the indices shared, in memory, until the file holds them:
// StoredIndices::leave_in_file), off the raster's critical path (0.2 s on the 2.1M sphere box,
// 0.9 s on the 10M terrain).
#include "core/mesh/hierarchy/cluster_cache.h"
#include "core/mesh/hierarchy/mesh_clusters.h"
#include "core/util/stage_times.h"

#include <filesystem>
#include <future>
#include <memory>
#include <string>

namespace irad {

class BackgroundClusters {
public:
  // Starts cached_mesh_clusters(scene, options, cache) on its own thread, once `after` (if
  // given) has its hierarchy (so that a second build leaves the cores to the first). `scene`
  // must outlive this object and stay unchanged until take() returns.
  BackgroundClusters(const Scene& scene, const ClusterOptions& options, std::filesystem::path cache,
                     const BackgroundClusters* after = nullptr);
  // Waits for the build and the cache write (a build that is never taken still runs to its end).
  ~BackgroundClusters();
  BackgroundClusters(const BackgroundClusters&) = delete;
  BackgroundClusters& operator=(const BackgroundClusters&) = delete;

  // Whether this is the build cached_mesh_clusters(scene, options, cache) would make, not yet
  // taken.
  bool builds(const Scene& scene, const ClusterOptions& options,
              const std::filesystem::path& cache) const;
  // The hierarchy, once: waits for it; rethrows what the build threw.
  MeshClusters take();
  // Where the hierarchy is built, not read from the cache: waits until the build has ended and
  // its cache file is written (or failed), without taking the hierarchy, for a caller that would
  // otherwise hold its own big arrays beside the build's. After a cache hit: returns without
  // waiting for the read.
  void wait_for_build() const;
  // After take(): the build's stages (as cached_mesh_clusters reports them, "cache write"
  // included) and the cache's outcome; both wait for the cache write.
  const StageTimes& times() const;
  const CacheResult& cache_result() const;

private:
  const Scene* scene_;
  ClusterOptions options_;
  std::filesystem::path cache_;
  StageTimes times_;   // written by the thread, read once it has ended
  CacheResult result_; // likewise
  std::promise<MeshClusters> hierarchy_;
  std::future<MeshClusters> future_; // the hierarchy
  std::promise<void> built_;         // set when the hierarchy (or its exception) is
  std::shared_future<void> built_future_;
  std::promise<bool> building_; // set once known: true for a build, false for a hit (or an error)
  std::shared_future<bool> building_future_;
  std::future<void> done_; // the thread: the build, then the cache write
};

// Where a renderer gets one hierarchy: from a build started earlier, where it builds what is
// wanted, else built here through the cache; with what that cost and what the cache did. Stages
// are named `name` + the build's stage ("hierarchy tree", "camera hierarchy cache read").
class ClusterSource {
public:
  // prebuilt: nullptr when none.
  ClusterSource(std::string name, std::filesystem::path cache,
                std::shared_ptr<BackgroundClusters> prebuilt);
  // The hierarchy (once): taken, its wait added to `times` as name + "wait", or built, its
  // stages added to `times`. The prebuilt build is not asked again either way.
  MeshClusters get(const Scene& scene, const ClusterOptions& wanted, StageTimes& times);
  // A taken hierarchy's own stages, which ran beside the caller's, its cache write included
  // (this waits for it); empty otherwise.
  StageTimes beside_times() const;
  // What the cache did (for a taken hierarchy: once its file is written; this waits).
  CacheResult cache_result() const;

private:
  std::string name_;
  std::filesystem::path cache_;
  std::shared_ptr<BackgroundClusters> prebuilt_;
  std::shared_ptr<const BackgroundClusters> taken_; // its cache file may still be written
  CacheResult cache_result_;                        // of a build here
};

} // namespace irad
