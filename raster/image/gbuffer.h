#pragma once
// The camera's G-buffer: for every pixel of the image the one surface it sees (the nearest, with
// alpha the nearest present one): world position (w = 1 where there is a surface, 0 for the
// background), the shading normal turned towards the camera, and the albedo (0 on mirrors). It
// is drawn once per image (CameraPasses::gbuffer) into RGBA32F textures over the target's depth
// buffer, and read by the deferred VPL passes (raster/passes/deferred_shader.h) and the
// interleaved resolve: every later pass shades exactly one surface per pixel, whatever lies
// behind it or coincides with it.
// A scene with a material that is not Lambertian (MaterialFeatures::glossy) has the glTF BRDF's
// inputs too (raster/glsl/shaders.h gbuffer_fragment): the normal's w is the roughness, the
// albedo is the directional albedo toward the camera, and two more textures hold (base colour,
// f90) and (f0, metallic).
#include "raster/context/gl_objects.h"

#include <glm/glm.hpp>
#include <utility>
#include <vector>

namespace irad::gl {

class GBuffer {
public:
  // depth: the target's depth renderbuffer (the G-buffer pass writes the depth the forward
  // passes and the emitters test against). glossy: with the BRDF's two textures.
  GBuffer(const GladGLContext& api, int width, int height, GLuint depth, bool glossy);

  int width() const { return width_; }
  int height() const { return height_; }
  bool glossy() const { return static_cast<bool>(base_); }
  // As draw framebuffer with the viewport on the whole image.
  void bind() const;
  // Binds position, normal and albedo to texture units first, first + 1, first + 2.
  void bind_textures(GLint first) const;
  // glossy(): binds (base, f90) and (f0, metallic) to units first and first + 1.
  void bind_brdf_textures(GLint first) const;
  // The positions and normals, row by row from the bottom (VisibilityRequest's layout): what
  // visibility by rays starts its shadow rays from.
  void read(std::vector<glm::vec4>& positions, std::vector<glm::vec4>& normals) const;
  // The position and normal of texel (x, y).
  std::pair<glm::vec4, glm::vec4> texel(int x, int y) const;
  // The camera it was drawn from, as the shaders' u_eye (raster/passes/camera_passes.h
  // eye_uniform): set by CameraPasses::gbuffer.
  const glm::vec4& eye() const { return eye_; }
  void set_eye(const glm::vec4& eye) { eye_ = eye; }

private:
  const GladGLContext* api_;
  int width_, height_;
  Texture position_, normal_, albedo_, base_, specular_;
  Framebuffer fbo_;
  glm::vec4 eye_{0.0f};
};

} // namespace irad::gl
