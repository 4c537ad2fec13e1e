#pragma once
// A scene's shadow hierarchy (core/mesh/mesh_clusters.h on the GPU: raster/shadow/shadow_lod.h),
// built on the first shadow face that needs it and kept for every atlas of one renderer: the
// batched passes are re-made when the shadow resolution changes, the hierarchy is not.
#include "core/mesh/cluster_cache.h"
#include "core/mesh/mesh_clusters.h"
#include "core/util/stage_times.h"
#include "raster/scene/gpu_scene.h"
#include "raster/shadow/shadow_lod.h"

#include <filesystem>
#include <memory>

namespace irad::gl {

class LodProvider {
public:
  // Nothing is built here. gpu must outlive this object. cache: the folder that keeps
  // hierarchies between runs (core/mesh/cluster_cache.h; empty: none).
  LodProvider(const GladGLContext& api, const GpuScene& gpu, const ShadowLodOptions& options,
              std::filesystem::path cache = {});

  // The hierarchy, built and uploaded on the first call; nullptr with ShadowLodMode::Off and for
  // an animated scene (its faces draw every triangle).
  const ShadowLod* get();
  // What building it cost: "hierarchy <stage>" for build_mesh_clusters's stages (or
  // "hierarchy cache read"; "hierarchy cache write" after a build), then "hierarchy upload";
  // empty before the first get() that built it.
  const StageTimes& setup_times() const { return times_; }
  const CacheResult& cache_result() const { return cache_result_; }

private:
  const GladGLContext* api_;
  const GpuScene* gpu_;
  ShadowLodOptions options_;
  std::filesystem::path cache_;
  CacheResult cache_result_;
  std::unique_ptr<ShadowLod> lod_;
  StageTimes times_;
};

} // namespace irad::gl
