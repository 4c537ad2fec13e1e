#pragma once
// The GL side of jittered sampling (raster/image/pixel_jitter.h): every pass that looks through a
// jittered projection needs the depth of that very projection, and the passes drawn once per
// image (visible emitters, the interleaved resolve's albedo) are averaged over a fixed set of
// jittered passes, so the whole image is filtered with the same box over the pixel footprint.
#include "core/camera/view.h"
#include "core/scene/scene.h"
#include "raster/context/shader_program.h"
#include "raster/image/gbuffer.h"
#include "raster/passes/background.h"
#include "raster/passes/camera_passes.h"
#include "raster/scene/gpu_scene.h"

#include <glm/glm.hpp>
#include <memory>

namespace irad::gl {

// Jittered passes of the emitters and of the albedo: 16, the reference's 4 x 4 supersampling.
inline constexpr int kCameraJitterPasses = 16;

class JitterPasses {
public:
  JitterPasses(const GladGLContext& api, const MaterialFeatures& features);
  // Clears the depth inside the bound framebuffer's viewport (only there: a tile of the
  // interleaved atlas) and writes the scene's depth seen through view_projection.
  void redraw_depth(const CameraPasses& camera, const glm::mat4& view_projection,
                    const GpuScene& gpu) const;
  // Adds L_e of the visible emitters, and the background (when not null) where no surface is
  // seen, averaged over kCameraJitterPasses jittered projections into the bound target (its
  // depth is redrawn for each, so it is left jittered): both get the same offsets and weights,
  // so the background's edges against the geometry antialias like the emitters'.
  void emitters(const CameraPasses& camera, const View& view, const Scene& scene,
                const GpuScene& gpu, const Background* background = nullptr) const;
  // The G-buffer of jitter cell `stratum` (raster/image/pixel_jitter.h): the scene seen through
  // the view's projection moved to the cell's centre, for the batched passes' deferred shading.
  // One G-buffer with its own depth, drawn anew by each call (the image's size on first use).
  const GBuffer& stratum_gbuffer(const CameraPasses& camera, const View& view, int stratum,
                                 const GpuScene& gpu);
  // With the interleaved G-buffer bound (albedo at colour attachment 2): replaces the albedo by
  // its average over kCameraJitterPasses jittered projections; position and normal stay the
  // pixel centre's (the resolve's geometry test), the shared depth is left jittered.
  void average_albedo(const CameraPasses& camera, const View& view, const GpuScene& gpu) const;

private:
  const GladGLContext* api_;
  ShaderProgram gbuffer_;
  MaterialUniforms material_;
  GLint vp_, eye_;
  Renderbuffer stratum_depth_;
  std::unique_ptr<GBuffer> stratum_gbuffer_;
};

} // namespace irad::gl
