#pragma once
// A scene's shadow hierarchy (core/mesh/mesh_clusters.h on the GPU: raster/shadow/shadow_lod.h),
// built on the first shadow face that needs it and kept for every atlas of one renderer: the
// batched passes are re-made when the shadow resolution changes, the hierarchy is not.
#include "core/mesh/mesh_clusters.h"
#include "core/util/stage_times.h"
#include "raster/scene/gpu_scene.h"
#include "raster/shadow/shadow_lod.h"

#include <memory>

namespace irad::gl {

class LodProvider {
public:
  // Nothing is built here. gpu must outlive this object.
  LodProvider(const GladGLContext& api, const GpuScene& gpu, const ShadowLodOptions& options);

  // The hierarchy, built and uploaded on the first call; nullptr with ShadowLodMode::Off and for
  // an animated scene (its faces draw every triangle).
  const ShadowLod* get();
  // What building it cost: "hierarchy <stage>" for build_mesh_clusters's stages, then
  // "hierarchy upload"; empty before the first get() that built it.
  const StageTimes& setup_times() const { return times_; }

private:
  const GladGLContext* api_;
  const GpuScene* gpu_;
  ShadowLodOptions options_;
  std::unique_ptr<ShadowLod> lod_;
  StageTimes times_;
};

} // namespace irad::gl
