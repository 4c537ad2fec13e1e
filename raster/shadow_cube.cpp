#include "raster/shadow_cube.h"

#include "core/error.h"
#include "core/light_sampler.h"
#include "raster/shaders.h"

#include <array>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace irad::gl {

namespace {

// Cube face axes in GL's face order (+x, -x, +y, -y, +z, -z): the look direction and the up
// vector that make a rendered face match GL's cube-map lookup convention.
struct FaceAxes {
  glm::vec3 forward;
  glm::vec3 up;
};
constexpr std::array<FaceAxes, 6> faces = {{{{1, 0, 0}, {0, -1, 0}},
                                            {{-1, 0, 0}, {0, -1, 0}},
                                            {{0, 1, 0}, {0, 0, 1}},
                                            {{0, -1, 0}, {0, 0, -1}},
                                            {{0, 0, 1}, {0, -1, 0}},
                                            {{0, 0, -1}, {0, -1, 0}}}};

// World -> cube frame. Surface VPLs: rows (t, b, n), so the normal maps to +z.
glm::mat3 cube_frame(const Vpl& vpl) {
  if (vpl.kind != VplKind::Surface) return glm::mat3(1.0f);
  glm::vec3 t, b;
  orthonormal_basis(vpl.normal, t, b);
  return glm::transpose(glm::mat3(t, b, vpl.normal));
}

} // namespace

// With the face axes above, window x runs toward -z on +x and toward +z on -x, window y toward +z
// on +y and toward -z on -y. One texel of margin covers lookups right at z = 0.
glm::ivec4 front_half(int f, int r) {
  const int h = r / 2 + 1;
  switch (f) {
  case 0:
    return {0, 0, h, r};
  case 1:
    return {r - h, 0, h, r};
  case 2:
    return {0, r - h, r, h};
  default:
    return {0, 0, r, h};
  }
}

CubeFaces cube_faces(const Vpl& vpl, const Bounds& bounds) {
  CubeFaces c;
  c.frame = cube_frame(vpl);
  c.hemisphere = vpl.kind == VplKind::Surface;
  // Near and far fitted to this VPL: far reaches the farthest corner of the scene's bounds.
  float far = 0.0f;
  for (int k = 0; k < 8; ++k) {
    const glm::vec3 p((k & 1) ? bounds.hi.x : bounds.lo.x, (k & 2) ? bounds.hi.y : bounds.lo.y,
                      (k & 4) ? bounds.hi.z : bounds.lo.z);
    far = glm::max(far, glm::length(p - vpl.position));
  }
  far = glm::max(1.01f * far, 1e-30f);
  c.far = far;
  const float near = 1e-4f * glm::max(bounds.diagonal(), far);
  const glm::mat4 projection = glm::perspective(glm::radians(90.0f), 1.0f, near, far);
  const glm::mat4 to_frame = glm::mat4(c.frame) * glm::translate(glm::mat4(1.0f), -vpl.position);
  for (int f = 0; f < 6; ++f) {
    const glm::mat4 face_view = glm::lookAt(glm::vec3(0.0f), faces[f].forward, faces[f].up);
    c.view_projection[f] = projection * face_view * to_frame;
  }
  return c;
}

Texture ShadowCube::make_cube(const GladGLContext& api, int resolution) {
  Texture cube = make_texture(api);
  api.BindTexture(GL_TEXTURE_CUBE_MAP, cube.get());
  for (int f = 0; f < 6; ++f)
    api.TexImage2D(static_cast<GLenum>(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), 0, GL_R32F, resolution,
                   resolution, 0, GL_RED, GL_FLOAT, nullptr);
  api.TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  api.TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  api.TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  api.TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  api.TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  return cube;
}

ShadowCube::ShadowCube(const GladGLContext& api, int resolution, const Bounds& bounds)
    : api_(&api), resolution_(resolution), bounds_(bounds),
      program_(api, "shadow", shaders::shadow_vertex, shaders::shadow_fragment),
      u_face_view_projection_(program_.uniform("u_face_view_projection")),
      u_vpl_position_(program_.uniform("u_vpl_position")), cube_(make_cube(api, resolution)),
      depth_(make_renderbuffer(api)) {
  api.BindRenderbuffer(GL_RENDERBUFFER, depth_.get());
  api.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, resolution, resolution);
  for (int f = 0; f < 6; ++f) {
    fbos_[f] = make_framebuffer(api);
    api.BindFramebuffer(GL_FRAMEBUFFER, fbos_[f].get());
    api.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.get());
    api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                             static_cast<GLenum>(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), cube_.get(),
                             0);
    check_framebuffer(api, "shadow cube framebuffer");
  }
  attached_ = cube_.get();
}

glm::mat3 ShadowCube::render_into(const Vpl& vpl, const GpuScene& scene, GLuint cube) {
  if (cube != attached_) {
    for (int f = 0; f < 6; ++f) {
      api_->BindFramebuffer(GL_FRAMEBUFFER, fbos_[f].get());
      api_->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                 static_cast<GLenum>(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), cube, 0);
    }
    attached_ = cube;
  }
  const CubeFaces cf = cube_faces(vpl, bounds_);
  api_->Viewport(0, 0, resolution_, resolution_);
  api_->Enable(GL_DEPTH_TEST);
  api_->DepthFunc(GL_LESS);
  api_->DepthMask(GL_TRUE);
  api_->Disable(GL_BLEND);
  api_->ClearColor(3.0e38f, 0.0f, 0.0f, 0.0f); // nothing there: never shadowed
  program_.use();
  api_->Uniform3fv(u_vpl_position_, 1, glm::value_ptr(vpl.position));
  const bool hemisphere = cf.hemisphere;
  for (int f = 0; f < 6; ++f) {
    if (f == kNegativeZFace && hemisphere) continue;
    api_->BindFramebuffer(GL_FRAMEBUFFER, fbos_[f].get());
    // A side face of a hemisphere cube is needed only on its +z half (plus one texel).
    const bool half = hemisphere && f < 4;
    if (half) {
      const glm::ivec4 r = front_half(f, resolution_);
      api_->Enable(GL_SCISSOR_TEST);
      api_->Scissor(r.x, r.y, r.z, r.w);
    }
    api_->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    api_->UniformMatrix4fv(u_face_view_projection_, 1, GL_FALSE,
                           glm::value_ptr(cf.view_projection[f]));
    scene.draw_all();
    if (half) api_->Disable(GL_SCISSOR_TEST);
  }
  return cf.frame;
}

} // namespace irad::gl
