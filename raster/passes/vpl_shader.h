#pragma once
// The shading pass of one VPL: draws the scene with w * C(x) (core/lights/vpl.h) into whatever
// framebuffer and viewport are bound, added by blending over a depth buffer that already holds
// the visible surface (GL_LEQUAL, no depth writes).
#include "core/lights/vpl.h"
#include "core/scene/mirrors.h"
#include "core/scene/scene.h"
#include "raster/context/shader_program.h"
#include "raster/scene/gpu_scene.h"
#include "raster/scene/material_glsl.h"
#include "raster/shadow/shadow_cube.h"

#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

namespace irad::gl {

// The normal offset of a shadow lookup in shadow texels (raster/glsl/cube_glsl.h lookup_offset).
// Where the occluder planes are drawn (`planes`: walls thinner than a texel's depth range,
// raster_renderer.h planes_needed) 0.5 texel: the lookup compares the receiver with the
// occluder's plane both ways (cube_glsl.h occluder_distance), so the offset need not cover the
// texel's depth range, and a smaller offset keeps receivers in narrow gaps out of the surface
// across the gap. Measured (godot_occlusion_room's stacked spheres, 128x128, R = 64, raster
// against rt-vpl over the same representatives, 4x4 blocks, no compensation): the lesser of the
// centre's distance and the plane with 1 texel 1.58e-3, 0.75 9.7e-4 (0.5 shadowed single pixels
// of a flat textured quad by 2.5 %, tests/test_material_features); the plane both ways with 0.75
// 7.0e-4, 0.5 4.0e-4, 0.2 5.9e-4 (means 1 % low, and the batched passes parted from the
// per-VPL ones on 0.4-0.5 % of the pixels). The 2 mm wall of tests/test_two_rooms leaks 4.1e-5
// of the lit room with 0.5 (4.0e-5 with 0.75; the concave corners of occluder_distance keep
// it there: without them 1.0e-4 with 0.5). Without them the lookup
// trusts the receiver's own plane (cube_glsl.h in_front_of_receiver), so the offset need not cover
// the texel's depth range (with the centre's distance alone it has to: 0.75 texel, half the texel's
// diagonal with a margin; 0.4 and below shadowed the surfaces themselves), and 0.2 is left for
// curved meshes, whose shading normal is not their triangle's. Measured on the Cornell box
// (256x256, R = 128, N = 1024, every VPL, interleave 1, against rt-vpl with the same VPLs,
// 4x4-block relMSE, the plane crossing alone): the centre alone with 0.75 texel 2.67e-5;
// 0.3 1.72e-5, 0.2 1.65e-5, 0.1 1.59e-5.
inline float normal_offset_texels(bool planes) {
  return planes ? 0.5f : 0.2f;
}

class VplShader {
public:
  // planes: whether the occluder planes are drawn (normal_offset_texels).
  VplShader(const GladGLContext& api, const Scene& scene, float clamp, bool planes);
  ~VplShader();
  // apply_albedo false: irradiance / pi without rho(x) (interleaved mode applies rho later).
  // Mirrors receive no light (their rho is 0 here). A mirrored VPL (core/scene/mirrors.h) is drawn
  // by a second program that lights only its pyramid (raster/glsl/mirror_shaders.h); that program
  // exists only for scenes with mirrors.
  void draw(const Vpl& vpl, const ShadowCube& shadow, const glm::mat3& frame,
            const glm::mat4& view_projection, bool apply_albedo, const GpuScene& gpu) const {
    draw(vpl, shadow.texture(), shadow.texel_angle(), frame, view_projection, apply_albedo, gpu);
  }
  // The same with any cube map ShadowCube::render_into drew (texel_angle of its resolution).
  void draw(const Vpl& vpl, GLuint shadow_cube, float texel_angle, const glm::mat3& frame,
            const glm::mat4& view_projection, bool apply_albedo, const GpuScene& gpu) const;
  // A scene with a material that is not Lambertian (IRAD_GLOSSY): the camera the next draws look
  // from (raster/passes/camera_passes.h eye_uniform), and the lobes their glossy VPLs index
  // (VplSet::lobes; nullptr: every VPL drawn as Lambertian; not owned, it must outlive the draws).
  void set_eye(const glm::vec4& eye) { eye_ = eye; }
  void set_lobes(const std::vector<VplLobe>* lobes) { lobes_ = lobes; }
  // Receivers of roughness below r shade only their diffuse lobe from the VPLs a ray can meet
  // (RasterOptions::traced_roughness); 0 (the default): none.
  void set_traced_roughness(float r) { traced_roughness_ = r; }
  // Whether the cubes the next draws read hold occluder planes (the constructor's `planes`).
  void set_planes(bool planes);

private:
  VplShader(const GladGLContext& api, const Scene& scene, float clamp, bool planes,
            const std::string& fragment);
  void set_mirror(const MirrorPolygon& mirror, const glm::vec4& plane) const;
  void draw_pass(const Vpl& vpl, GLuint shadow_cube, float texel_angle, const glm::mat3& frame,
                 const glm::mat4& view_projection, bool apply_albedo, const GpuScene& gpu) const;

  void set_lobe(const Vpl& vpl) const;

  std::unique_ptr<VplShader> mirrored_; // the program for mirrored VPLs, with mirrors only
  std::vector<MirrorPolygon> mirrors_;
  GLint mirror_plane_ = -1, mirror_triangles_ = -1, mirror_corners_ = -1;
  const GladGLContext* api_;
  float diagonal_, clamp_;
  ShaderProgram program_;
  MaterialUniforms material_;
  GLint view_projection_, position_, normal_, intensity_, kind_, spot_cos_, dmin2_, min_dist2_,
      frame_, bias_constant_, bias_texel_, apply_albedo_, eye_uniform_, lobe_, reachable_, traced_;
  float traced_roughness_ = 0.0f;
  bool glossy_;
  glm::vec4 eye_{0.0f};
  const std::vector<VplLobe>* lobes_ = nullptr;
};

// A glossy VPL's lobe as the shaders read it (raster/glsl/deferred_shaders.h BatchVpl::lobe):
// (base, metallic), (f0, f90), (incident, roughness), (a(incident), 1), the incident direction
// reflected for a mirrored VPL (core/lights/vpl.h vpl_lobe_shape); all 0 without a lobe.
std::array<float, 16> lobe_record(const Vpl& vpl, const VplLobe* lobe);

// Texture units shared by the raster's programs.
inline constexpr GLint shadow_unit = 0;
inline constexpr GLint material_unit = 1; // base colour texture
inline constexpr GLint emissive_unit = 2; // emissive texture
// The glTF BRDF's textures and tables (raster/scene/material_glsl.h, IRAD_GLOSSY and
// IRAD_NORMAL_MAP): read by the camera passes and the per-VPL passes.
inline constexpr GLint metallic_roughness_unit = 3;
inline constexpr GLint specular_unit = 4;
inline constexpr GLint specular_color_unit = 5;
inline constexpr GLint normal_unit = 6;
inline constexpr GLint albedo_table_unit = 7; // GpuScene::albedo_table

// Additive passes over an existing depth buffer: exactly the visible surface passes GL_LEQUAL.
void set_additive_state(const GladGLContext& api);

} // namespace irad::gl
