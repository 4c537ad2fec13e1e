#pragma once
// Directional lights in the raster: a directional VPL (a light at infinity, core/lights/vpl.h) gets
// an orthographic shadow map over the scene (raster/shadow/ortho_shadow.h, shared by all VPLs of
// one direction) and a shading pass that adds w * C(x) = I max(0, n . -d) V rho(x)/pi into whatever
// framebuffer and viewport are bound, over a depth buffer holding the visible surface (as
// raster/passes/vpl_shader.h). Built only for scenes with a directional light or an environment.
#include "core/lights/vpl.h"
#include "core/scene/scene.h"
#include "raster/context/shader_program.h"
#include "raster/scene/gpu_scene.h"
#include "raster/scene/material_glsl.h"
#include "raster/shadow/ortho_shadow.h"

#include <glm/glm.hpp>

namespace irad::gl {

class DirectionalPass {
public:
  DirectionalPass(const GladGLContext& api, const Scene& scene, int resolution);

  // The shadow map for vpl's direction (may change the bound framebuffer, viewport, program).
  void shadow(const Vpl& vpl, const GpuScene& gpu) { map_.render(vpl.normal, gpu); }
  // The next shadow() renders anew (call when the geometry may have changed).
  void forget() { map_.forget(); }
  // apply_albedo false: irradiance / pi without rho(x) (interleaved mode applies rho later).
  void draw(const Vpl& vpl, const glm::mat4& view_projection, bool apply_albedo,
            const GpuScene& gpu) const;
  int resolution() const { return map_.resolution(); }

private:
  const GladGLContext* api_;
  OrthoShadow map_;
  ShaderProgram program_;
  MaterialUniforms material_;
  GLint view_projection_, direction_, intensity_, lookup_, texel_, apply_albedo_;
};

// Whether the walk can emit directional VPLs for `scene`: it has a directional punctual light or
// an environment that is not black (each environment VPL a direction of its own).
bool has_directional_light(const Scene& scene);

} // namespace irad::gl
