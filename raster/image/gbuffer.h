#pragma once
// The camera's G-buffer: for every pixel of the image the one surface it sees (the nearest, with
// alpha the nearest present one): world position (w = 1 where there is a surface, 0 for the
// background), the shading normal turned towards the camera, and the diffuse albedo (0 on
// mirrors). It is drawn once per image (CameraPasses::gbuffer) into three RGBA32F textures over
// the target's depth buffer, and read by the deferred VPL passes (raster/passes/deferred_shader.h)
// and the interleaved resolve: every later pass shades exactly one surface per pixel, whatever
// lies behind it or coincides with it.
#include "raster/context/gl_objects.h"

namespace irad::gl {

class GBuffer {
public:
  // depth: the target's depth renderbuffer (the G-buffer pass writes the depth the forward
  // passes and the emitters test against).
  GBuffer(const GladGLContext& api, int width, int height, GLuint depth);

  int width() const { return width_; }
  int height() const { return height_; }
  // As draw framebuffer with the viewport on the whole image.
  void bind() const;
  // Binds position, normal and albedo to texture units first, first + 1, first + 2.
  void bind_textures(GLint first) const;

private:
  const GladGLContext* api_;
  int width_, height_;
  Texture position_, normal_, albedo_;
  Framebuffer fbo_;
};

} // namespace irad::gl
