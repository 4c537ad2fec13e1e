#include "raster/passes/camera_passes.h"

#include "raster/glsl/brdf_glsl.h"
#include "raster/glsl/shaders.h"
#include "raster/passes/vpl_shader.h"

#include <glm/gtc/type_ptr.hpp>
#include <string>

namespace irad::gl {

namespace {

// The G-buffer's fragment shader; lambertian: for a glossy scene's Lambertian materials.
std::string gbuffer_source(const MaterialFeatures& features, bool lambertian) {
  std::string s = material_source(shaders::gbuffer_fragment, features);
  if (lambertian) s.insert(s.find('\n') + 1, "#define IRAD_LAMBERTIAN_MATERIALS 1\n");
  return shaders::with_brdf(s);
}

} // namespace

CameraPasses::GBufferProgram::GBufferProgram(const GladGLContext& api,
                                             const MaterialFeatures& features, bool lambertian)
    : program(api, "gbuffer", material_source(shaders::camera_vertex, features),
              gbuffer_source(features, lambertian)),
      material(program), view_projection(program.uniform("u_view_projection")),
      eye(program.uniform("u_eye")), simplified(program.uniform("u_simplified")) {}

CameraPasses::CameraPasses(const GladGLContext& api, const MaterialFeatures& features)
    : api_(&api), depth_(api, "depth", material_source(shaders::camera_vertex, features),
                         material_source(shaders::depth_fragment, features)),
      emission_(api, "emission", material_source(shaders::camera_vertex, features),
                material_source(shaders::emission_fragment, features)),
      gbuffer_(api, features, false),
      lambertian_gbuffer_(features.glossy ? std::make_unique<GBufferProgram>(api, features, true)
                                          : nullptr),
      depth_material_(depth_), emission_material_(emission_),
      depth_vp_(depth_.uniform("u_view_projection")),
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
                           const GpuScene& gpu, const CameraLod* lod) const {
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
  if (!lambertian_gbuffer_) {
    draw_gbuffer(gbuffer_, view_projection, eye, gpu, lod, [](const Material&) { return true; });
    return;
  }
  draw_gbuffer(*lambertian_gbuffer_, view_projection, eye, gpu, lod, MaterialUniforms::lambertian);
  draw_gbuffer(gbuffer_, view_projection, eye, gpu, lod,
               [](const Material& m) { return !MaterialUniforms::lambertian(m); });
}

void CameraPasses::draw_gbuffer(const GBufferProgram& p, const glm::mat4& view_projection,
                                const glm::vec4& eye, const GpuScene& gpu, const CameraLod* lod,
                                const std::function<bool(const Material&)>& select) const {
  const GladGLContext& api = *api_;
  p.program.use();
  api.UniformMatrix4fv(p.view_projection, 1, GL_FALSE, glm::value_ptr(view_projection));
  api.Uniform4fv(p.eye, 1, glm::value_ptr(eye));
  api.Uniform1i(p.simplified, lod ? 1 : 0);
  const auto bind = [&](const Material& m) {
    const glm::vec3 rho = m.specular ? glm::vec3(0.0f) : m.base_color; // mirrors: no diffuse
    p.material.bind_base(api, gpu, m, rho);
  };
  if (lod)
    lod->draw_if(select, bind);
  else
    gpu.draw_if(select, bind);
}

void CameraPasses::emitters(const glm::mat4& view_projection, const Scene& scene,
                            const GpuScene& gpu, float weight, const CameraLod* lod) const {
  if (!scene.has_emitters()) return;
  const GladGLContext& api = *api_;
  set_additive_state(api);
  if (weight != 1.0f) {
    api.BlendColor(0.0f, 0.0f, 0.0f, weight);
    api.BlendFunc(GL_CONSTANT_ALPHA, GL_ONE);
  }
  emission_.use();
  api.UniformMatrix4fv(emission_vp_, 1, GL_FALSE, glm::value_ptr(view_projection));
  const auto emissive = [](const Material& m) { return m.emissive(); };
  const auto bind = [&](const Material& m) {
    api.Uniform1i(emission_double_sided_, m.double_sided ? 1 : 0);
    emission_material_.bind_emission(api, gpu, m);
  };
  if (lod)
    lod->draw_if(emissive, bind);
  else
    gpu.draw_if(emissive, bind);
}

} // namespace irad::gl
