#pragma once
// The passes that see the scene from the camera once per image: depth only (the surface every
// VPL pass then adds to), the G-buffer for interleaved sampling, and the visible emitters' L_e.
#include "core/scene.h"
#include "raster/gpu_scene.h"
#include "raster/shader_program.h"

#include <glm/glm.hpp>

namespace irad::gl {

class CameraPasses {
public:
  explicit CameraPasses(const GladGLContext& api);
  // Writes depth only (colour masked) into the bound framebuffer's viewport (clear it first:
  // glClear ignores the viewport).
  void depth(const glm::mat4& view_projection, const GpuScene& gpu) const;
  // Clears and writes position, normal and albedo (three colour attachments) and depth.
  void gbuffer(const glm::mat4& view_projection, const GpuScene& gpu) const;
  // Adds weight * L_e of the visible emitters (front faces unless double-sided) over the bound
  // depth (weight < 1: one of several jittered passes, raster/jitter_passes.h).
  void emitters(const glm::mat4& view_projection, const Scene& scene, const GpuScene& gpu,
                float weight = 1.0f) const;

private:
  const GladGLContext* api_;
  ShaderProgram depth_, gbuffer_, emission_;
  GLint depth_vp_;
  GLint gbuffer_vp_, gbuffer_base_color_, gbuffer_has_texture_;
  GLint emission_vp_, emission_radiance_, emission_has_texture_, emission_double_sided_;
};

} // namespace irad::gl
