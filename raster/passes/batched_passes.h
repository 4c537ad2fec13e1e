#pragma once
// Batched, deferred VPL passes (RasterOptions::batch > 1): the VPLs are drawn B at a time, the
// shadow cubes of a batch into one atlas by one instanced draw (raster/shadow/shadow_atlas.h),
// then the batch's shading screen-space from the camera's G-buffer by one full-screen draw per
// interleaved set (raster/passes/deferred_shader.h). The image is the one the per-VPL passes give
// where every pixel sees one surface (the same cube faces, the same shading maths at the same
// point; tests/test_batched.cpp measures the difference); where faces coincide the per-VPL
// passes light each of them, these passes the one surface the G-buffer kept. What changes is the
// cost: per batch 2 binds, 1 clear, 1 + k^2 draws, and a shading cost of pixels x VPLs that does
// not depend on the triangles, against 6 binds, 5 clears and 6 draws of the whole scene per VPL.
// Directional and mirrored VPLs, jitter and the cached shadow maps keep the per-VPL passes.
#include "core/scene.h"
#include "core/vpl.h"
#include "raster/context/pass_timer.h"
#include "raster/image/gbuffer.h"
#include "raster/image/interleaved.h"
#include "raster/image/target.h"
#include "raster/passes/deferred_shader.h"
#include "raster/scene/gpu_scene.h"
#include "raster/shadow/shadow_atlas.h"

#include <functional>
#include <memory>
#include <vector>

namespace irad::gl {

class BatchedPasses {
public:
  // Batches of up to `batch` VPLs (fewer if this GL's texture or uniform-block sizes ask for
  // it) with resolution^2 cube faces; nullptr when batch < 2 or not even 2 VPLs fit.
  static std::unique_ptr<BatchedPasses> make(const GladGLContext& api, const Scene& scene,
                                             float clamp, int batch, int resolution);
  BatchedPasses(const GladGLContext& api, const Scene& scene, float clamp, int requested, int batch,
                int resolution);

  // Whether this object serves make(..., batch, resolution).
  bool matches(int batch, int resolution) const {
    return batch == requested_ && resolution == atlas_.resolution();
  }

  // Draws the VPLs that carry light (none directional or mirrored) batch by batch: shadow atlas,
  // then the shading of each set (set_of(vpl)) from `gbuffer` into its tile of `interleaved`, or
  // (nullptr) of all into the target. After each batch `after` gets the number of VPLs of `vpls`
  // done; false stops. Returns the number of VPLs drawn.
  std::size_t draw(const std::vector<const Vpl*>& vpls,
                   const std::function<int(const Vpl&)>& set_of, const GBuffer& gbuffer,
                   const Interleaved* interleaved, const Target& target, const GpuScene& gpu,
                   PassTimer* timer, const std::function<bool(std::size_t)>& after);

private:
  struct Entry {
    const Vpl* vpl;
    int set;
  };
  // Draws the batch (ordered by set on the way).
  void flush(std::vector<Entry>& batch, const GBuffer& gbuffer, const Interleaved* interleaved,
             const Target& target, const GpuScene& gpu, PassTimer* timer);

  int requested_;
  ShadowAtlas atlas_;
  DeferredShader shader_;
  std::vector<const Vpl*> vpls_;
  std::vector<glm::mat3> frames_;
  std::vector<float> fars_;
  std::vector<glm::ivec4> blocks_;
};

} // namespace irad::gl
