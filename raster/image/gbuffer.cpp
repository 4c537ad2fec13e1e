#include "raster/image/gbuffer.h"

namespace irad::gl {

GBuffer::GBuffer(const GladGLContext& api, int width, int height, GLuint depth, bool glossy)
    : api_(&api), width_(width), height_(height), position_(make_float_texture(api, width, height)),
      normal_(make_float_texture(api, width, height)),
      albedo_(make_float_texture(api, width, height)), fbo_(make_framebuffer(api)) {
  if (glossy) {
    base_ = make_float_texture(api, width, height);
    specular_ = make_float_texture(api, width, height);
  }
  api.BindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  const GLuint textures[5] = {position_.get(), normal_.get(), albedo_.get(), base_.get(),
                              specular_.get()};
  const GLenum buffers[5] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                             GL_COLOR_ATTACHMENT3, GL_COLOR_ATTACHMENT4};
  const int count = glossy ? 5 : 3;
  for (int i = 0; i < count; ++i)
    api.FramebufferTexture2D(GL_FRAMEBUFFER, buffers[i], GL_TEXTURE_2D, textures[i], 0);
  api.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  api.DrawBuffers(count, buffers);
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

void GBuffer::bind_brdf_textures(GLint first) const {
  const GLuint textures[2] = {base_.get(), specular_.get()};
  for (GLint i = 0; i < 2; ++i) {
    api_->ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + first + i));
    api_->BindTexture(GL_TEXTURE_2D, textures[i]);
  }
}

std::pair<glm::vec4, glm::vec4> GBuffer::texel(int x, int y) const {
  std::pair<glm::vec4, glm::vec4> out;
  api_->BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_.get());
  api_->PixelStorei(GL_PACK_ALIGNMENT, 4);
  api_->ReadBuffer(GL_COLOR_ATTACHMENT0);
  api_->ReadPixels(x, y, 1, 1, GL_RGBA, GL_FLOAT, &out.first.x);
  api_->ReadBuffer(GL_COLOR_ATTACHMENT1);
  api_->ReadPixels(x, y, 1, 1, GL_RGBA, GL_FLOAT, &out.second.x);
  api_->ReadBuffer(GL_COLOR_ATTACHMENT0);
  return out;
}

void GBuffer::read(std::vector<glm::vec4>& positions, std::vector<glm::vec4>& normals) const {
  const std::size_t texels = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  positions.resize(texels);
  normals.resize(texels);
  api_->BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_.get());
  api_->PixelStorei(GL_PACK_ALIGNMENT, 4);
  api_->ReadBuffer(GL_COLOR_ATTACHMENT0);
  api_->ReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, positions.data());
  api_->ReadBuffer(GL_COLOR_ATTACHMENT1);
  api_->ReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, normals.data());
  api_->ReadBuffer(GL_COLOR_ATTACHMENT0);
}

} // namespace irad::gl
