#include "raster/passes/camera_passes.h"

#include "raster/glsl/brdf_glsl.h"
#include "raster/glsl/shaders.h"
#include "raster/passes/vpl_shader.h"

#include <glm/gtc/type_ptr.hpp>

namespace irad::gl {

CameraPasses::CameraPasses(const GladGLContext& api, const MaterialFeatures& features)
    : api_(&api), depth_(api, "depth", material_source(shaders::camera_vertex, features),
                         material_source(shaders::depth_fragment, features)),
      gbuffer_(api, "gbuffer", material_source(shaders::camera_vertex, features),
               shaders::with_brdf(material_source(shaders::gbuffer_fragment, features))),
      emission_(api, "emission", material_source(shaders::camera_vertex, features),
                material_source(shaders::emission_fragment, features)),
      depth_material_(depth_), gbuffer_material_(gbuffer_), emission_material_(emission_),
      depth_vp_(depth_.uniform("u_view_projection")),
      gbuffer_vp_(gbuffer_.uniform("u_view_projection")),
      gbuffer_eye_(gbuffer_.optional_uniform("u_eye")),
      emission_vp_(emission_.uniform("u_view_projection")),
      emission_double_sided_(emission_.uniform("u_double_sided")) {}

void CameraPasses::depth(const glm::mat4& view_projection, const GpuScene& gpu) const {
  const GladGLContext& api = *api_;
  api.Disable(GL_BLEND);
  api.Enable(GL_DEPTH_TEST);
  api.DepthFunc(GL_LESS);
  api.DepthMask(GL_TRUE);
  api.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  depth_.use();
  api.UniformMatrix4fv(depth_vp_, 1, GL_FALSE, glm::value_ptr(view_projection));
  gpu.draw_covered(1, [&](const Material& m) { depth_material_.bind_alpha(api, gpu, m); });
  api.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void CameraPasses::gbuffer(GBuffer& target, const glm::mat4& view_projection, const glm::vec4& eye,
                           const GpuScene& gpu) const {
  const GladGLContext& api = *api_;
  target.bind();
  target.set_eye(eye);
  api.Disable(GL_BLEND);
  api.Enable(GL_DEPTH_TEST);
  api.DepthFunc(GL_LESS);
  api.DepthMask(GL_TRUE);
  api.ClearColor(0.0f, 0.0f, 0.0f, 0.0f); // position w = 0: no surface
  api.ClearDepth(1.0);
  api.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gbuffer_.use();
  api.UniformMatrix4fv(gbuffer_vp_, 1, GL_FALSE, glm::value_ptr(view_projection));
  api.Uniform4fv(gbuffer_eye_, 1, glm::value_ptr(eye));
  gpu.draw([&](const Material& m) {
    const glm::vec3 rho = m.specular ? glm::vec3(0.0f) : m.base_color; // mirrors: no diffuse
    gbuffer_material_.bind_base(api, gpu, m, rho);
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
                api.Uniform1i(emission_double_sided_, m.double_sided ? 1 : 0);
                emission_material_.bind_emission(api, gpu, m);
              });
}

} // namespace irad::gl
