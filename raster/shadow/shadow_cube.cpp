#include "raster/shadow/shadow_cube.h"

#include "core/lights/light_sampler.h"
#include "core/scene/mirrors.h"
#include "core/util/error.h"
#include "raster/glsl/mirror_shaders.h"
#include "raster/glsl/shaders.h"

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

float far_from(const Bounds& bounds, const glm::vec3& position) {
  // Far reaches the farthest corner of the scene's bounds.
  float far = 0.0f;
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 p((c & 1) ? bounds.hi.x : bounds.lo.x, (c & 2) ? bounds.hi.y : bounds.lo.y,
                      (c & 4) ? bounds.hi.z : bounds.lo.z);
    far = glm::max(far, glm::length(p - position));
  }
  return far;
}

CubeFaces cube_faces(const Vpl& vpl, const Bounds& bounds, float far) {
  CubeFaces c;
  c.frame = cube_frame(vpl);
  c.hemisphere = vpl.kind == VplKind::Surface;
  // Near and far fitted to this VPL.
  c.far = glm::max(1.01f * far, 1e-30f);
  const float near = 1e-4f * glm::max(bounds.diagonal(), c.far);
  const glm::mat4 projection = glm::perspective(glm::radians(90.0f), 1.0f, near, c.far);
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
    api.TexImage2D(static_cast<GLenum>(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), 0, GL_RGBA32F,
                   resolution, resolution, 0, GL_RGBA, GL_FLOAT, nullptr);
  api.TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  api.TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  api.TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  api.TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  api.TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  return cube;
}

ShadowCube::ShadowCube(const GladGLContext& api, int resolution, const Bounds& bounds,
                       const MaterialFeatures& features)
    : api_(&api), resolution_(resolution), bounds_(bounds), features_(features),
      program_(api, "shadow", material_source(shaders::shadow_vertex, features),
               material_source(shaders::shadow_fragment, features)),
      material_(program_), u_face_view_projection_(program_.uniform("u_face_view_projection")),
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

float ShadowCube::far_from(const glm::vec3& position) const {
  return gl::far_from(bounds_, position);
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
  if (vpl.mirror >= 0) return render_mirrored(vpl, scene);
  program_.use();
  api_->Uniform3fv(u_vpl_position_, 1, glm::value_ptr(vpl.position));
  return render_faces(vpl, far_from(vpl.position), [&](const glm::mat4& vp) {
    api_->UniformMatrix4fv(u_face_view_projection_, 1, GL_FALSE, glm::value_ptr(vp));
    scene.draw_covered(1, [&](const Material& m) { material_.bind_alpha(*api_, scene, m); });
  });
}

// The mirrored VPL's cube (raster/glsl/mirror_shaders.h): the real scene and its reflection, both
// clipped to the lit side of the plane. The reflected scene is as far from y' as the real one
// is from y.
glm::mat3 ShadowCube::render_mirrored(const Vpl& vpl, const GpuScene& scene) {
  if (!mirror_) mirror_ = std::make_unique<MirrorProgram>(*api_, features_);
  const MirrorProgram& m = *mirror_;
  const glm::vec3 n(vpl.mirror_plane);
  // Reflection x -> x - 2 (n . x + w) n as a matrix; the clip plane moved 1e-5 of the diagonal
  // to the lit side, so the mirror's own plane never shadows.
  glm::mat4 reflect(glm::mat3(1.0f) - 2.0f * glm::outerProduct(n, n));
  reflect[3] = glm::vec4(-2.0f * vpl.mirror_plane.w * n, 1.0f);
  const glm::vec4 clip = vpl.mirror_plane - glm::vec4(0.0f, 0.0f, 0.0f, 1e-5f * bounds_.diagonal());
  const float far =
      glm::max(far_from(vpl.position), far_from(reflect_point(vpl.mirror_plane, vpl.position)));
  m.program.use();
  api_->Uniform3fv(m.vpl_position, 1, glm::value_ptr(vpl.position));
  api_->Uniform4fv(m.clip_plane, 1, glm::value_ptr(clip));
  api_->Enable(GL_CLIP_DISTANCE0);
  const glm::mat3 frame = render_faces(vpl, far, [&](const glm::mat4& vp) {
    api_->UniformMatrix4fv(m.face_view_projection, 1, GL_FALSE, glm::value_ptr(vp));
    for (const glm::mat4& r : {glm::mat4(1.0f), reflect}) {
      api_->UniformMatrix4fv(m.reflect, 1, GL_FALSE, glm::value_ptr(r));
      scene.draw_covered(1, [&](const Material& mat) { m.material.bind_alpha(*api_, scene, mat); });
    }
  });
  api_->Disable(GL_CLIP_DISTANCE0);
  return frame;
}

ShadowCube::MirrorProgram::MirrorProgram(const GladGLContext& api, const MaterialFeatures& features)
    : program(api, "mirror shadow", material_source(shaders::mirror_shadow_vertex, features),
              material_source(shaders::shadow_fragment, features)),
      material(program), face_view_projection(program.uniform("u_face_view_projection")),
      vpl_position(program.uniform("u_vpl_position")), reflect(program.uniform("u_reflect")),
      clip_plane(program.uniform("u_clip_plane")) {}

glm::mat3 ShadowCube::render_faces(const Vpl& vpl, float far,
                                   const std::function<void(const glm::mat4&)>& draw) {
  const CubeFaces cube = cube_faces(vpl, bounds_, far);
  api_->Viewport(0, 0, resolution_, resolution_);
  api_->Enable(GL_DEPTH_TEST);
  api_->DepthFunc(GL_LESS);
  api_->DepthMask(GL_TRUE);
  api_->Disable(GL_BLEND);
  api_->ClearColor(3.0e38f, 0.0f, 0.0f, 0.0f); // nothing there: never shadowed
  for (int f = 0; f < 6; ++f) {
    if (f == kNegativeZFace && cube.hemisphere) continue;
    api_->BindFramebuffer(GL_FRAMEBUFFER, fbos_[f].get());
    // A side face of a hemisphere cube is needed only on its +z half (plus one texel).
    const bool half = cube.hemisphere && f < 4;
    if (half) {
      const glm::ivec4 r = front_half(f, resolution_);
      api_->Enable(GL_SCISSOR_TEST);
      api_->Scissor(r.x, r.y, r.z, r.w);
    }
    api_->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    draw(cube.view_projection[f]);
    if (half) api_->Disable(GL_SCISSOR_TEST);
  }
  return cube.frame;
}

} // namespace irad::gl
