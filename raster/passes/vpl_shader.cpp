#include "raster/passes/vpl_shader.h"

#include "raster/glsl/brdf_glsl.h"
#include "raster/glsl/cube_glsl.h"
#include "raster/glsl/mirror_shaders.h"
#include "raster/glsl/shaders.h"

#include <algorithm>

#include <glm/gtc/type_ptr.hpp>

namespace irad::gl {

void set_additive_state(const GladGLContext& api) {
  api.Enable(GL_DEPTH_TEST);
  api.DepthFunc(GL_LEQUAL);
  api.DepthMask(GL_FALSE);
  api.Enable(GL_BLEND);
  api.BlendEquation(GL_FUNC_ADD);
  api.BlendFunc(GL_ONE, GL_ONE);
}

VplShader::VplShader(const GladGLContext& api, const Scene& scene, float clamp, bool planes)
    : VplShader(api, scene, clamp, planes, shaders::vpl_fragment) {
  if (!scene.has_specular()) return;
  mirrors_ = find_mirrors(scene);
  mirrored_.reset(new VplShader(api, scene, clamp, planes,
                                shaders::mirror_vpl_fragment(shaders::vpl_fragment)));
  const ShaderProgram& p = mirrored_->program_;
  mirrored_->mirror_plane_ = p.uniform("u_mirror_plane");
  mirrored_->mirror_triangles_ = p.uniform("u_mirror_triangles");
  mirrored_->mirror_corners_ = p.uniform("u_mirror_corners");
}

VplShader::~VplShader() = default;

std::array<float, 16> lobe_record(const Vpl& vpl, const VplLobe* lobe) {
  std::array<float, 16> r{};
  if (lobe == nullptr) return r;
  const BrdfInputs& m = lobe->material;
  const glm::vec3 incident = lobe_incident(*lobe, vpl);
  r = {m.base.x,       m.base.y,       m.base.z,       m.metallic, m.f0.x,     m.f0.y,
       m.f0.z,         m.f90,          incident.x,     incident.y, incident.z, m.roughness,
       lobe->albedo.x, lobe->albedo.y, lobe->albedo.z, 1.0f};
  return r;
}

void VplShader::set_lobe(const Vpl& vpl) const {
  const std::array<float, 16> r = lobe_record(vpl, lobes_ ? find_lobe(*lobes_, vpl) : nullptr);
  api_->Uniform4fv(lobe_, 4, r.data());
  api_->Uniform4fv(eye_uniform_, 1, glm::value_ptr(eye_));
  api_->Uniform1i(reachable_, vpl.ray_reachable() ? 1 : 0);
  api_->Uniform1f(traced_, traced_roughness_);
}

void VplShader::set_mirror(const MirrorPolygon& mirror, const glm::vec4& plane) const {
  program_.use();
  api_->Uniform4fv(mirror_plane_, 1, glm::value_ptr(plane));
  const std::size_t triangles = std::min(mirror.triangles.size() / 3, MirrorPolygon::max_triangles);
  api_->Uniform1i(mirror_triangles_, static_cast<GLint>(triangles));
  api_->Uniform3fv(mirror_corners_, static_cast<GLsizei>(3 * triangles),
                   glm::value_ptr(mirror.triangles.front()));
}

VplShader::VplShader(const GladGLContext& api, const Scene& scene, float clamp, bool planes,
                     const std::string& fragment)
    : api_(&api), diagonal_(scene.bounds.diagonal()), clamp_(clamp),
      program_(api, "vpl", material_source(shaders::camera_vertex, MaterialFeatures::of(scene)),
               shaders::with_brdf(shaders::with_cube_lookup(
                   material_source(fragment, MaterialFeatures::of(scene))))),
      material_(program_), view_projection_(program_.uniform("u_view_projection")),
      position_(program_.uniform("u_vpl_position")), normal_(program_.uniform("u_vpl_normal")),
      intensity_(program_.uniform("u_vpl_intensity")), kind_(program_.uniform("u_vpl_kind")),
      spot_cos_(program_.uniform("u_spot_cos")), dmin2_(program_.uniform("u_dmin2")),
      min_dist2_(program_.uniform("u_min_dist2")), frame_(program_.uniform("u_shadow_frame")),
      bias_constant_(program_.uniform("u_bias_constant")),
      bias_texel_(program_.uniform("u_bias_texel")),
      apply_albedo_(program_.uniform("u_apply_albedo")),
      eye_uniform_(program_.optional_uniform("u_eye")), lobe_(program_.optional_uniform("u_lobe")),
      reachable_(program_.optional_uniform("u_vpl_reachable")),
      traced_(program_.optional_uniform("u_traced_roughness")), glossy_(!scene.all_lambertian()) {
  // Samplers of different types may not share a unit: fix every sampler's unit once.
  program_.use();
  api.Uniform1i(program_.uniform("u_shadow"), shadow_unit);
  // Scale-relative constants: the clamp, the coincidence guard and the shadow bias.
  api.Uniform1f(min_dist2_, 1e-10f * diagonal_ * diagonal_); // 1e-5 of the diagonal, as rt-vpl
  api.Uniform1f(bias_constant_, 2e-4f * diagonal_);
  set_planes(planes);
}

void VplShader::set_planes(bool planes) {
  program_.use();
  api_->Uniform1f(program_.uniform("u_offset_texels"), normal_offset_texels(planes));
  api_->Uniform1i(program_.uniform("u_planes"), planes ? 1 : 0);
  if (mirrored_) mirrored_->set_planes(planes);
}

void VplShader::draw(const Vpl& vpl, GLuint shadow_cube, float texel_angle, const glm::mat3& frame,
                     const glm::mat4& view_projection, bool apply_albedo,
                     const GpuScene& gpu) const {
  if (vpl.mirror >= 0) { // a mirrored VPL: the pyramid program (nothing if the scene has none)
    const auto k = static_cast<std::size_t>(vpl.mirror);
    if (!mirrored_ || k >= mirrors_.size()) return;
    mirrored_->eye_ = eye_;
    mirrored_->lobes_ = lobes_;
    mirrored_->traced_roughness_ = traced_roughness_;
    mirrored_->set_mirror(mirrors_[k], vpl.mirror_plane);
    mirrored_->draw_pass(vpl, shadow_cube, texel_angle, frame, view_projection, apply_albedo, gpu);
    return;
  }
  draw_pass(vpl, shadow_cube, texel_angle, frame, view_projection, apply_albedo, gpu);
}

void VplShader::draw_pass(const Vpl& vpl, GLuint shadow_cube, float texel_angle,
                          const glm::mat3& frame, const glm::mat4& view_projection,
                          bool apply_albedo, const GpuScene& gpu) const {
  const GladGLContext& api = *api_;
  set_additive_state(api);
  program_.use();
  api.UniformMatrix4fv(view_projection_, 1, GL_FALSE, glm::value_ptr(view_projection));
  api.Uniform3fv(position_, 1, glm::value_ptr(vpl.position));
  api.Uniform3fv(normal_, 1, glm::value_ptr(vpl.normal));
  api.Uniform3fv(intensity_, 1, glm::value_ptr(vpl.intensity));
  api.Uniform1i(kind_, static_cast<GLint>(vpl.kind));
  api.Uniform2f(spot_cos_, vpl.cos_inner, vpl.cos_outer);
  api.Uniform1f(dmin2_, clamp_distance2(vpl, clamp_ * diagonal_));
  api.UniformMatrix3fv(frame_, 1, GL_FALSE, glm::value_ptr(frame));
  api.Uniform1f(bias_texel_, texel_angle);
  api.Uniform1i(apply_albedo_, apply_albedo ? 1 : 0);
  api.ActiveTexture(GL_TEXTURE0 + shadow_unit);
  api.BindTexture(GL_TEXTURE_CUBE_MAP, shadow_cube);
  if (glossy_) set_lobe(vpl);
  if (!apply_albedo && !glossy_) {
    gpu.draw_covered(1, [&](const Material& m) { material_.bind_alpha(api, gpu, m); });
    return;
  }
  gpu.draw([&](const Material& m) {
    const glm::vec3 rho = m.specular ? glm::vec3(0.0f) : m.base_color; // mirrors: no diffuse
    material_.bind_base(api, gpu, m, rho);
  });
}

} // namespace irad::gl
