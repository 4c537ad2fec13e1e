#pragma once
// The passes that see the scene from the camera once per image: depth only (the surface every
// VPL pass then adds to), the G-buffer for interleaved sampling, and the visible emitters' L_e.
#include "core/camera/view.h"
#include "core/scene/scene.h"
#include "raster/context/shader_program.h"
#include "raster/image/gbuffer.h"
#include "raster/passes/camera_lod.h"
#include "raster/scene/gpu_scene.h"
#include "raster/scene/material_glsl.h"

#include <functional>
#include <glm/glm.hpp>
#include <memory>

namespace irad::gl {

// The shaders' u_eye (raster/glsl/brdf_glsl.h toward_eye): (eye, 1) for a pinhole camera, (the
// direction toward it, 0) for an orthographic one.
inline glm::vec4 eye_uniform(const View& view) {
  return view.orthographic ? glm::vec4(-view.forward, 0.0f) : glm::vec4(view.eye, 1.0f);
}

class CameraPasses {
public:
  CameraPasses(const GladGLContext& api, const MaterialFeatures& features);
  // Writes depth only (colour masked) into the bound framebuffer's viewport (clear it first:
  // glClear ignores the viewport).
  void depth(const glm::mat4& view_projection, const GpuScene& gpu) const;
  // Binds `target`, clears and writes its colour attachments (raster/image/gbuffer.h) and depth,
  // and records `eye` (eye_uniform: the glossy albedo and shading look toward it) in it.
  // lod: the camera's hierarchy prepared for this view (raster/passes/camera_lod.h), drawn
  // instead of every triangle; nullptr: every triangle.
  void gbuffer(GBuffer& target, const glm::mat4& view_projection, const glm::vec4& eye,
               const GpuScene& gpu, const CameraLod* lod = nullptr) const;
  // Adds weight * L_e of the visible emitters (front faces unless double-sided) over the bound
  // depth (weight < 1: one of several jittered passes, raster/image/jitter_passes.h). lod: as
  // for gbuffer, the one the depth was drawn with (the same triangles pass the depth test).
  void emitters(const glm::mat4& view_projection, const Scene& scene, const GpuScene& gpu,
                float weight = 1.0f, const CameraLod* lod = nullptr) const;

private:
  // A G-buffer program and its uniforms.
  struct GBufferProgram {
    GBufferProgram(const GladGLContext& api, const MaterialFeatures& features, bool lambertian);
    ShaderProgram program;
    MaterialUniforms material;
    GLint view_projection, eye, simplified;
  };
  // Draws the materials `select` picks with p.
  void draw_gbuffer(const GBufferProgram& p, const glm::mat4& view_projection, const glm::vec4& eye,
                    const GpuScene& gpu, const CameraLod* lod,
                    const std::function<bool(const Material&)>& select) const;

  const GladGLContext* api_;
  ShaderProgram depth_, emission_;
  // gbuffer_ draws every material; in a glossy scene lambertian_gbuffer_ draws the Lambertian
  // ones without the BRDF's code (raster/glsl/shaders.h IRAD_LAMBERTIAN_MATERIALS).
  GBufferProgram gbuffer_;
  std::unique_ptr<GBufferProgram> lambertian_gbuffer_;
  MaterialUniforms depth_material_, emission_material_;
  GLint depth_vp_;
  GLint emission_vp_, emission_double_sided_;
};

} // namespace irad::gl
