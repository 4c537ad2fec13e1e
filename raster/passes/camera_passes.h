#pragma once
// The passes that see the scene from the camera once per image: depth only (the surface every
// VPL pass then adds to), the G-buffer for interleaved sampling, and the visible emitters' L_e.
#include "core/scene/scene.h"
#include "raster/context/shader_program.h"
#include "raster/scene/gpu_scene.h"
#include "raster/scene/material_glsl.h"

#include <glm/glm.hpp>

namespace irad::gl {

class CameraPasses {
public:
  CameraPasses(const GladGLContext& api, const MaterialFeatures& features);
  // Writes depth only (colour masked) into the bound framebuffer's viewport (clear it first:
  // glClear ignores the viewport).
  void depth(const glm::mat4& view_projection, const GpuScene& gpu) const;
  // Clears and writes position, normal and albedo (three colour attachments) and depth.
  void gbuffer(const glm::mat4& view_projection, const GpuScene& gpu) const;
  // Adds weight * L_e of the visible emitters (front faces unless double-sided) over the bound
  // depth (weight < 1: one of several jittered passes, raster/image/jitter_passes.h).
  void emitters(const glm::mat4& view_projection, const Scene& scene, const GpuScene& gpu,
                float weight = 1.0f) const;

private:
  const GladGLContext* api_;
  ShaderProgram depth_, gbuffer_, emission_;
  MaterialUniforms depth_material_, gbuffer_material_, emission_material_;
  GLint depth_vp_;
  GLint gbuffer_vp_;
  GLint emission_vp_, emission_double_sided_;
};

} // namespace irad::gl
