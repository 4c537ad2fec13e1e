#include "raster/image/target.h"

#include "core/util/error.h"

#include <string>

namespace irad::gl {

Target::Target(const GladGLContext& api, int width, int height)
    : api_(&api), width_(width), height_(height), color_(make_texture(api)),
      depth_(make_renderbuffer(api)), fbo_(make_framebuffer(api)) {
  GLint max_size = 0;
  api.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (width < 1 || height < 1 || width > max_size || height > max_size)
    throw Error("", "--size",
                std::to_string(width) + "x" + std::to_string(height) +
                    " is outside what this OpenGL allows (1.." + std::to_string(max_size) + ")");
  api.BindTexture(GL_TEXTURE_2D, color_.get());
  api.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  api.BindTexture(GL_TEXTURE_2D, 0); // never bound for sampling while it is rendered into
  api.BindRenderbuffer(GL_RENDERBUFFER, depth_.get());
  api.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, width, height);
  api.BindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_.get(), 0);
  api.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.get());
  check_framebuffer(api, "accumulation framebuffer");
}

void Target::bind() const {
  api_->BindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  api_->Viewport(0, 0, width_, height_);
}

Image Target::read() const {
  Image image(width_, height_);
  api_->BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_.get());
  api_->ReadBuffer(GL_COLOR_ATTACHMENT0);
  api_->PixelStorei(GL_PACK_ALIGNMENT, 4);
  std::vector<glm::vec4> rows(static_cast<std::size_t>(width_) * height_);
  api_->ReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, rows.data());
  // GL's row 0 is the bottom of the image.
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      glm::vec4 p = rows[static_cast<std::size_t>(height_ - 1 - y) * width_ + x];
      p.a = 1.0f;
      image.at(x, y) = p;
    }
  return image;
}

} // namespace irad::gl
