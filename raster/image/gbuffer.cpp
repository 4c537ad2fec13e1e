#include "raster/image/gbuffer.h"

namespace irad::gl {

GBuffer::GBuffer(const GladGLContext& api, int width, int height, GLuint depth)
    : api_(&api), width_(width), height_(height), position_(make_float_texture(api, width, height)),
      normal_(make_float_texture(api, width, height)),
      albedo_(make_float_texture(api, width, height)), fbo_(make_framebuffer(api)) {
  api.BindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, position_.get(), 0);
  api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, normal_.get(), 0);
  api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, GL_TEXTURE_2D, albedo_.get(), 0);
  api.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
  api.DrawBuffers(3, buffers);
  check_framebuffer(api, "G-buffer framebuffer");
}

void GBuffer::bind() const {
  api_->BindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  api_->Viewport(0, 0, width_, height_);
}

void GBuffer::bind_textures(GLint first) const {
  const GLuint textures[3] = {position_.get(), normal_.get(), albedo_.get()};
  for (GLint i = 0; i < 3; ++i) {
    api_->ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + first + i));
    api_->BindTexture(GL_TEXTURE_2D, textures[i]);
  }
}

} // namespace irad::gl
