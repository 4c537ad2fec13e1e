#include "raster/passes/directional_pass.h"

#include "raster/glsl/directional_shaders.h"
#include "raster/glsl/shaders.h"
#include "raster/passes/vpl_shader.h"

#include <algorithm>
#include <glm/gtc/type_ptr.hpp>

namespace irad::gl {

bool has_directional_light(const Scene& scene) {
  if (scene.has_environment())
    return true; // its VPLs are directional (core/lights/light_sampler.h)
  return std::any_of(scene.lights.begin(), scene.lights.end(), [](const PunctualLight& l) {
    return l.kind == PunctualLight::Kind::Directional;
  });
}

DirectionalPass::DirectionalPass(const GladGLContext& api, const Scene& scene, int resolution)
    : api_(&api), map_(api, resolution, scene.bounds, MaterialFeatures::of(scene)),
      program_(api, "directional",
               material_source(shaders::camera_vertex, MaterialFeatures::of(scene)),
               material_source(shaders::directional_fragment, MaterialFeatures::of(scene))),
      material_(program_), view_projection_(program_.uniform("u_view_projection")),
      direction_(program_.uniform("u_direction")), intensity_(program_.uniform("u_intensity")),
      lookup_(program_.uniform("u_light_lookup")), texel_(program_.uniform("u_texel")),
      apply_albedo_(program_.uniform("u_apply_albedo")) {
  program_.use();
  api.Uniform1i(program_.uniform("u_shadow"), shadow_unit);
  // Scale-relative: the same constant bias as the cube maps' (raster/passes/vpl_shader.cpp).
  api.Uniform1f(program_.uniform("u_bias_constant"), 2e-4f * scene.bounds.diagonal());
  api.Uniform1f(texel_, map_.texel());
}

void DirectionalPass::draw(const Vpl& vpl, const glm::mat4& view_projection, bool apply_albedo,
                           const GpuScene& gpu) const {
  const GladGLContext& api = *api_;
  set_additive_state(api);
  program_.use();
  api.UniformMatrix4fv(view_projection_, 1, GL_FALSE, glm::value_ptr(view_projection));
  api.Uniform3fv(direction_, 1, glm::value_ptr(vpl.normal));
  api.Uniform3fv(intensity_, 1, glm::value_ptr(vpl.intensity));
  api.UniformMatrix4fv(lookup_, 1, GL_FALSE, glm::value_ptr(map_.lookup()));
  api.Uniform1i(apply_albedo_, apply_albedo ? 1 : 0);
  api.ActiveTexture(GL_TEXTURE0 + shadow_unit);
  api.BindTexture(GL_TEXTURE_2D, map_.texture());
  if (!apply_albedo) {
    gpu.draw_covered(1, [&](const Material& m) { material_.bind_alpha(api, gpu, m); });
    return;
  }
  gpu.draw([&](const Material& m) { material_.bind_base(api, gpu, m, m.base_color); });
}

} // namespace irad::gl
