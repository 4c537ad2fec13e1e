#pragma once
// A scene's shadow hierarchy (core/mesh/hierarchy/mesh_clusters.h on the GPU:
// raster/shadow/shadow_lod.h), built on the first shadow face that needs it and kept for every
// atlas of one renderer: the batched passes are re-made when the shadow resolution changes, the
// hierarchy is not.
#include "core/mesh/hierarchy/background_clusters.h"
#include "core/mesh/hierarchy/cluster_cache.h"
#include "core/mesh/hierarchy/mesh_clusters.h"
#include "core/util/stage_times.h"
#include "raster/scene/gpu_scene.h"
#include "raster/shadow/shadow_lod.h"

#include <filesystem>
#include <memory>

namespace irad::gl {

class LodProvider {
public:
  // Nothing is built here. gpu must outlive this object. cache: the folder that keeps
  // hierarchies between runs (core/mesh/hierarchy/cluster_cache.h; empty: none). prebuilt: a build
  // started earlier (core/mesh/hierarchy/background_clusters.h), taken instead of building where it
  // builds what get() needs.
  LodProvider(const GladGLContext& api, const GpuScene& gpu, const ShadowLodOptions& options,
              std::filesystem::path cache = {},
              std::shared_ptr<BackgroundClusters> prebuilt = nullptr);
  // Keeps the levels the faces built (ShadowLod::build_levels) beside the hierarchy's cache file
  // (core/mesh/hierarchy/late_levels_file.h), for the next render of the scene.
  ~LodProvider();
  LodProvider(const LodProvider&) = delete;
  LodProvider& operator=(const LodProvider&) = delete;

  // The hierarchy, built (or taken) on the first call (its pages reach the GPU as the faces
  // first draw them: ShadowLod::make_resident); nullptr with
  // ShadowLodMode::Off and for an animated scene (its faces draw every triangle).
  const ShadowLod* get();
  // What getting it cost this thread: "hierarchy <stage>" for build_mesh_clusters's stages (or
  // "hierarchy cache read"; "hierarchy cache write" after a build), or "hierarchy wait" for the
  // time spent waiting on a prebuilt one; then "hierarchy upload" (the ShadowLod's set-up; the
  // page copies count in the passes that draw them). Empty before the first get()
  // that built it.
  const StageTimes& setup_times() const { return times_; }
  // A prebuilt hierarchy's own stages (as setup_times names them), which ran beside this
  // thread's, its cache write included (this waits for it); empty otherwise.
  StageTimes beside_times() const { return source_.beside_times(); }
  // What the cache did (for a prebuilt hierarchy: once its file is written; this waits).
  CacheResult cache_result() const { return source_.cache_result(); }
  // The bytes of its pages on the GPU (ShadowLod::gpu_bytes; 0 before get()).
  std::size_t gpu_bytes() const { return lod_ ? lod_->gpu_bytes() : 0; }
  // The deferred levels its faces built so far (ShadowLod::late_levels; none before get()), and
  // the nodes whose levels the cache's late file gave.
  ShadowLod::LateLevels late_levels() const {
    return lod_ ? lod_->late_levels() : ShadowLod::LateLevels{};
  }
  std::size_t late_levels_read() const { return lod_ ? late_read_ : 0; }

private:
  void keep_late_levels() noexcept;

  const GladGLContext* api_;
  const GpuScene* gpu_;
  ShadowLodOptions options_;
  ClusterSource source_;
  std::unique_ptr<ShadowLod> lod_;
  std::size_t late_read_ = 0;
  StageTimes times_;
};

} // namespace irad::gl
