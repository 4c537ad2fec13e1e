#pragma once
// The accumulation target: an RGBA32F colour texture and a 32-bit float depth buffer.
#include "core/image/image.h"
#include "raster/context/gl_objects.h"

namespace irad::gl {

class Target {
public:
  // Throws irad::Error when the size exceeds GL_MAX_RENDERBUFFER_SIZE or the framebuffer is
  // incomplete.
  Target(const GladGLContext& api, int width, int height);
  int width() const { return width_; }
  int height() const { return height_; }
  void bind() const;                            // as draw framebuffer, with the viewport set
  GLuint depth() const { return depth_.get(); } // the depth renderbuffer (shared with a G-buffer)
  // Reads the accumulated values (row 0 at the top) with alpha set to 1.
  Image read() const;

private:
  const GladGLContext* api_;
  int width_, height_;
  Texture color_;
  Renderbuffer depth_;
  Framebuffer fbo_;
};

} // namespace irad::gl
