#include "raster/image/jitter_passes.h"

#include "raster/glsl/brdf_glsl.h"
#include "raster/glsl/shaders.h"
#include "raster/image/pixel_jitter.h"
#include "raster/passes/vpl_shader.h"

#include <glm/gtc/type_ptr.hpp>

namespace irad::gl {

namespace {

glm::mat4 camera_pass(const View& view, int s) {
  return jittered_projection(view.projection, camera_jitter(s, kCameraJitterPasses), view.width,
                             view.height) *
         view.view;
}

// Blending that adds weight * source: the average of several passes, drawn one after another.
void set_weighted_add(const GladGLContext& api, float weight) {
  api.Enable(GL_BLEND);
  api.BlendEquation(GL_FUNC_ADD);
  api.BlendColor(0.0f, 0.0f, 0.0f, weight);
  api.BlendFunc(GL_CONSTANT_ALPHA, GL_ONE);
}

} // namespace

JitterPasses::JitterPasses(const GladGLContext& api, const MaterialFeatures& features)
    : api_(&api),
      gbuffer_(api, "jitter albedo", material_source(shaders::camera_vertex, features),
               shaders::with_brdf(material_source(shaders::gbuffer_fragment, features))),
      material_(gbuffer_), vp_(gbuffer_.uniform("u_view_projection")),
      eye_(gbuffer_.optional_uniform("u_eye")) {}

void JitterPasses::redraw_depth(const CameraPasses& camera, const glm::mat4& view_projection,
                                const GpuScene& gpu) const {
  const GladGLContext& api = *api_;
  GLint viewport[4];
  api.GetIntegerv(GL_VIEWPORT, viewport);
  api.Enable(GL_SCISSOR_TEST);
  api.Scissor(viewport[0], viewport[1], viewport[2], viewport[3]);
  api.DepthMask(GL_TRUE);
  api.ClearDepth(1.0);
  api.Clear(GL_DEPTH_BUFFER_BIT);
  api.Disable(GL_SCISSOR_TEST);
  camera.depth(view_projection, gpu);
}

void JitterPasses::emitters(const CameraPasses& camera, const View& view, const Scene& scene,
                            const GpuScene& gpu, const Background* background) const {
  if (!scene.has_emitters() && background == nullptr) return;
  const float weight = 1.0f / static_cast<float>(kCameraJitterPasses);
  for (int s = 0; s < kCameraJitterPasses; ++s) {
    const glm::mat4 vp = camera_pass(view, s);
    redraw_depth(camera, vp, gpu);
    camera.emitters(vp, scene, gpu, weight);
    if (background) background->draw(view, vp, weight);
  }
}

const GBuffer& JitterPasses::stratum_gbuffer(const CameraPasses& camera, const View& view,
                                             int stratum, const GpuScene& gpu) {
  const GladGLContext& api = *api_;
  if (!stratum_gbuffer_ || stratum_gbuffer_->width() != view.width ||
      stratum_gbuffer_->height() != view.height) {
    stratum_gbuffer_.reset();
    stratum_depth_ = make_renderbuffer(api);
    api.BindRenderbuffer(GL_RENDERBUFFER, stratum_depth_.get());
    api.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, view.width, view.height);
    stratum_gbuffer_ = std::make_unique<GBuffer>(api, view.width, view.height, stratum_depth_.get(),
                                                 gpu.features().glossy);
  }
  api.DepthMask(GL_TRUE);
  camera.gbuffer(
      *stratum_gbuffer_,
      jittered_projection(view.projection, stratum_offset(stratum), view.width, view.height) *
          view.view,
      eye_uniform(view), gpu);
  return *stratum_gbuffer_;
}

void JitterPasses::average_albedo(const CameraPasses& camera, const View& view,
                                  const GpuScene& gpu) const {
  const GladGLContext& api = *api_;
  const GLfloat zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  api.ClearBufferfv(GL_COLOR, 2, zero);
  for (int s = 0; s < kCameraJitterPasses; ++s) {
    const glm::mat4 vp = camera_pass(view, s);
    redraw_depth(camera, vp, gpu);
    // Only the albedo attachment; camera.depth() re-enabled every colour mask.
    api.ColorMaski(0, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    api.ColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    if (gpu.features().glossy) { // the BRDF's inputs stay the pixel centre's
      api.ColorMaski(3, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
      api.ColorMaski(4, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    }
    set_additive_state(api);
    set_weighted_add(api, 1.0f / static_cast<float>(kCameraJitterPasses));
    gbuffer_.use();
    api.UniformMatrix4fv(vp_, 1, GL_FALSE, glm::value_ptr(vp));
    api.Uniform4fv(eye_, 1, glm::value_ptr(eye_uniform(view)));
    gpu.draw([&](const Material& m) { // mirrors: no diffuse albedo, as CameraPasses::gbuffer
      material_.bind_base(api, gpu, m, m.specular ? glm::vec3(0.0f) : m.base_color);
    });
  }
  api.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

} // namespace irad::gl
