#pragma once
// The shading pass of one VPL: draws the scene with w * C(x) (core/vpl.h) into whatever
// framebuffer and viewport are bound, added by blending over a depth buffer that already holds
// the visible surface (GL_LEQUAL, no depth writes).
#include "core/mirrors.h"
#include "core/scene.h"
#include "core/vpl.h"
#include "raster/context/shader_program.h"
#include "raster/scene/gpu_scene.h"
#include "raster/scene/material_glsl.h"
#include "raster/shadow/shadow_cube.h"

#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

namespace irad::gl {

class VplShader {
public:
  VplShader(const GladGLContext& api, const Scene& scene, float clamp);
  ~VplShader();
  // apply_albedo false: irradiance / pi without rho(x) (interleaved mode applies rho later).
  // Mirrors receive no light (their rho is 0 here). A mirrored VPL (core/mirrors.h) is drawn by a
  // second program that lights only its pyramid (raster/glsl/mirror_shaders.h); that program exists
  // only for scenes with mirrors.
  void draw(const Vpl& vpl, const ShadowCube& shadow, const glm::mat3& frame,
            const glm::mat4& view_projection, bool apply_albedo, const GpuScene& gpu) const {
    draw(vpl, shadow.texture(), shadow.texel_angle(), frame, view_projection, apply_albedo, gpu);
  }
  // The same with any cube map ShadowCube::render_into drew (texel_angle of its resolution).
  void draw(const Vpl& vpl, GLuint shadow_cube, float texel_angle, const glm::mat3& frame,
            const glm::mat4& view_projection, bool apply_albedo, const GpuScene& gpu) const;

private:
  VplShader(const GladGLContext& api, const Scene& scene, float clamp, const std::string& fragment);
  void set_mirror(const MirrorPolygon& mirror, const glm::vec4& plane) const;
  void draw_pass(const Vpl& vpl, GLuint shadow_cube, float texel_angle, const glm::mat3& frame,
                 const glm::mat4& view_projection, bool apply_albedo, const GpuScene& gpu) const;

  std::unique_ptr<VplShader> mirrored_; // the program for mirrored VPLs, with mirrors only
  std::vector<MirrorPolygon> mirrors_;
  GLint mirror_plane_ = -1, mirror_triangles_ = -1, mirror_corners_ = -1;
  const GladGLContext* api_;
  float diagonal_, clamp_;
  ShaderProgram program_;
  MaterialUniforms material_;
  GLint view_projection_, position_, normal_, intensity_, kind_, spot_cos_, dmin2_, min_dist2_,
      frame_, bias_constant_, bias_texel_, apply_albedo_;
};

// Texture units shared by the raster's programs.
inline constexpr GLint shadow_unit = 0;
inline constexpr GLint material_unit = 1; // base colour texture
inline constexpr GLint emissive_unit = 2; // emissive texture

// Additive passes over an existing depth buffer: exactly the visible surface passes GL_LEQUAL.
void set_additive_state(const GladGLContext& api);

} // namespace irad::gl
