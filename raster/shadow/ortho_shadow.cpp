#include "raster/shadow/ortho_shadow.h"

#include "core/lights/light_sampler.h"
#include "raster/glsl/directional_shaders.h"

#include <algorithm>
#include <glm/gtc/type_ptr.hpp>

namespace irad::gl {

float ortho_half_width(const Bounds& bounds) {
  return std::max(0.505f * bounds.diagonal(), 1e-30f);
}

glm::mat4 ortho_light_matrix(const glm::vec3& d, const glm::vec3& c, float sx, float ox, float sz) {
  glm::vec3 t, b;
  orthonormal_basis(d, t, b);
  const glm::mat4 rows(glm::vec4(sx * t, ox - sx * glm::dot(t, c)),
                       glm::vec4(sx * b, ox - sx * glm::dot(b, c)),
                       glm::vec4(sz * d, -sz * glm::dot(d, c)), glm::vec4(0, 0, 0, 1));
  return glm::transpose(rows); // glm's constructor takes columns
}

int ortho_resolution_for(int requested, int width, int height) {
  if (requested > 0) return requested;
  int r = 256;
  while (r < 4096 && r < 2 * std::max(width, height)) r *= 2;
  return r;
}

OrthoShadow::OrthoShadow(const GladGLContext& api, int resolution, const Bounds& bounds,
                         const MaterialFeatures& features)
    : api_(&api), resolution_(resolution), centre_(bounds.center()),
      half_width_(ortho_half_width(bounds)),
      program_(api, "ortho shadow", material_source(shaders::ortho_shadow_vertex, features),
               material_source(shaders::ortho_shadow_fragment, features)),
      material_(program_), u_light_clip_(program_.uniform("u_light_clip")),
      u_centre_(program_.uniform("u_centre")), u_direction_(program_.uniform("u_direction")),
      map_(make_texture(api)), depth_(make_renderbuffer(api)), fbo_(make_framebuffer(api)) {
  api.BindTexture(GL_TEXTURE_2D, map_.get());
  api.TexImage2D(GL_TEXTURE_2D, 0, GL_R32F, resolution, resolution, 0, GL_RED, GL_FLOAT, nullptr);
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  api.BindTexture(GL_TEXTURE_2D, 0);
  api.BindRenderbuffer(GL_RENDERBUFFER, depth_.get());
  api.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, resolution, resolution);
  api.BindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  api.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.get());
  api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, map_.get(), 0);
  check_framebuffer(api, "orthographic shadow framebuffer");
}

bool OrthoShadow::render(const glm::vec3& d, const GpuScene& scene) {
  if (valid_ && d == direction_) return false;
  // Clip space: x, y over the square of half width h around c, z = d.(p - c) / h in [-1, 1]
  // (the bounding sphere), so GL_LESS keeps the surface nearest to the light.
  const float inv = 1.0f / half_width_;
  const glm::mat4 clip = ortho_light_matrix(d, centre_, inv, 0.0f, inv);
  lookup_ = ortho_light_matrix(d, centre_, 0.5f * inv, 0.5f, 1.0f);
  api_->BindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  api_->Viewport(0, 0, resolution_, resolution_);
  api_->Enable(GL_DEPTH_TEST);
  api_->DepthFunc(GL_LESS);
  api_->DepthMask(GL_TRUE);
  api_->Disable(GL_BLEND);
  api_->ClearColor(3.0e38f, 0.0f, 0.0f, 0.0f); // nothing there: never shadowed
  api_->ClearDepth(1.0);
  api_->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  program_.use();
  api_->UniformMatrix4fv(u_light_clip_, 1, GL_FALSE, glm::value_ptr(clip));
  api_->Uniform3fv(u_centre_, 1, glm::value_ptr(centre_));
  api_->Uniform3fv(u_direction_, 1, glm::value_ptr(d));
  scene.draw_covered(1, [&](const Material& m) { material_.bind_alpha(*api_, scene, m); });
  direction_ = d;
  valid_ = true;
  return true;
}

} // namespace irad::gl
