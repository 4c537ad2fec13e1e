#pragma once
// Batched VPL passes (RasterOptions::batch > 1): the VPLs are drawn B at a time, the shadow cubes
// of a batch into one atlas by one instanced draw (raster/shadow/shadow_atlas.h), then the batch's
// shading by one instanced draw per interleaved set (raster/passes/batched_shader.h). The image is the
// one the per-VPL passes give (the same cube faces, the same shading maths, the same
// view-projection and viewport per set; tests/test_batched.cpp measures the difference); what
// changes is the number of framebuffer binds, clears, draw calls and waits: per batch 2 binds,
// 1 clear and 1 + k^2 draws against 6 binds, 5 clears and 6 draws per VPL. Directional VPLs,
// jitter and the cached shadow maps keep the per-VPL passes.
#include "core/scene.h"
#include "core/view.h"
#include "core/vpl.h"
#include "raster/passes/batched_shader.h"
#include "raster/scene/gpu_scene.h"
#include "raster/image/interleaved.h"
#include "raster/context/pass_timer.h"
#include "raster/shadow/shadow_atlas.h"
#include "raster/image/target.h"

#include <functional>
#include <memory>
#include <vector>

namespace irad::gl {

class BatchedPasses {
public:
  // Batches of up to `batch` VPLs (fewer if this GL's texture or uniform-block sizes ask for
  // it) with resolution^2 cube faces; nullptr when batch < 2 or not even 2 VPLs fit.
  static std::unique_ptr<BatchedPasses> make(const GladGLContext& api, const Scene& scene,
                                             float clamp, int batch, int resolution,
                                             const ShadowLodOptions& lod);
  BatchedPasses(const GladGLContext& api, const Scene& scene, float clamp, int requested, int batch,
                int resolution, const ShadowLodOptions& lod);

  // Whether this object serves make(..., batch, resolution).
  bool matches(int batch, int resolution) const {
    return batch == requested_ && resolution == atlas_.resolution();
  }

  // Draws the VPLs that carry light (none directional) batch by batch: shadow atlas, then the
  // shading of each set (set_of(vpl)) into its tile of `interleaved`, or (nullptr) of all into
  // the target, over the depth the per-VPL passes use. After each batch `after` gets the number
  // of VPLs of `vpls` done; false stops. Returns the number of VPLs drawn.
  std::size_t draw(const View& view, const std::vector<const Vpl*>& vpls,
                   const std::function<int(const Vpl&)>& set_of, const Interleaved* interleaved,
                   const Target& target, const GpuScene& gpu, PassTimer* timer,
                   const std::function<bool(std::size_t)>& after);

private:
  struct Entry {
    const Vpl* vpl;
    int set;
  };
  // Draws the batch (ordered by set on the way).
  void flush(const View& view, std::vector<Entry>& batch, const Interleaved* interleaved,
             const Target& target, const GpuScene& gpu, PassTimer* timer);

  int requested_;
  ShadowAtlas atlas_;
  BatchedShader shader_;
  std::vector<const Vpl*> vpls_;
  std::vector<glm::mat3> frames_;
  std::vector<float> fars_;
  std::vector<glm::ivec4> blocks_;
};

} // namespace irad::gl
