#include "raster/camera_passes.h"

#include "raster/shaders.h"
#include "raster/vpl_shader.h"

#include <glm/gtc/type_ptr.hpp>

namespace irad::gl {

CameraPasses::CameraPasses(const GladGLContext& api)
    : api_(&api), depth_(api, "depth", shaders::camera_vertex, shaders::depth_fragment),
      gbuffer_(api, "gbuffer", shaders::camera_vertex, shaders::gbuffer_fragment),
      emission_(api, "emission", shaders::camera_vertex, shaders::emission_fragment),
      depth_vp_(depth_.uniform("u_view_projection")),
      gbuffer_vp_(gbuffer_.uniform("u_view_projection")),
      gbuffer_base_color_(gbuffer_.uniform("u_base_color")),
      gbuffer_has_texture_(gbuffer_.uniform("u_has_base_texture")),
      emission_vp_(emission_.uniform("u_view_projection")),
      emission_radiance_(emission_.uniform("u_emission")),
      emission_has_texture_(emission_.uniform("u_has_emissive_texture")),
      emission_double_sided_(emission_.uniform("u_double_sided")) {
  gbuffer_.use();
  api.Uniform1i(gbuffer_.uniform("u_base_texture"), material_unit);
  emission_.use();
  api.Uniform1i(emission_.uniform("u_emissive_texture"), material_unit);
}

void CameraPasses::depth(const glm::mat4& view_projection, const GpuScene& gpu) const {
  const GladGLContext& api = *api_;
  api.Disable(GL_BLEND);
  api.Enable(GL_DEPTH_TEST);
  api.DepthFunc(GL_LESS);
  api.DepthMask(GL_TRUE);
  api.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  depth_.use();
  api.UniformMatrix4fv(depth_vp_, 1, GL_FALSE, glm::value_ptr(view_projection));
  gpu.draw_all();
  api.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void CameraPasses::gbuffer(const glm::mat4& view_projection, const GpuScene& gpu) const {
  const GladGLContext& api = *api_;
  api.Disable(GL_BLEND);
  api.Enable(GL_DEPTH_TEST);
  api.DepthFunc(GL_LESS);
  api.DepthMask(GL_TRUE);
  api.ClearColor(0.0f, 0.0f, 0.0f, 0.0f); // position w = 0: no surface
  api.ClearDepth(1.0);
  api.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gbuffer_.use();
  api.UniformMatrix4fv(gbuffer_vp_, 1, GL_FALSE, glm::value_ptr(view_projection));
  gpu.draw([&](const Material& m) {
    const glm::vec3 rho = m.specular ? glm::vec3(0.0f) : m.base_color; // mirrors: no diffuse
    api.Uniform3fv(gbuffer_base_color_, 1, glm::value_ptr(rho));
    bind_material_texture(api, gpu, m.base_color_texture, gbuffer_has_texture_);
  });
}

void CameraPasses::emitters(const glm::mat4& view_projection, const Scene& scene,
                            const GpuScene& gpu, float weight) const {
  if (!scene.has_emitters()) return;
  const GladGLContext& api = *api_;
  set_additive_state(api);
  if (weight != 1.0f) {
    api.BlendColor(0.0f, 0.0f, 0.0f, weight);
    api.BlendFunc(GL_CONSTANT_ALPHA, GL_ONE);
  }
  emission_.use();
  api.UniformMatrix4fv(emission_vp_, 1, GL_FALSE, glm::value_ptr(view_projection));
  gpu.draw_if([](const Material& m) { return m.emissive(); },
              [&](const Material& m) {
                api.Uniform3fv(emission_radiance_, 1, glm::value_ptr(m.emission));
                api.Uniform1i(emission_double_sided_, m.double_sided ? 1 : 0);
                bind_material_texture(api, gpu, m.emissive_texture, emission_has_texture_);
              });
}

} // namespace irad::gl
