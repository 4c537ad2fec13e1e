#pragma once
// RAII owners of GL object names. Each holds the function table it was created with and deletes
// its name when it goes out of scope; they move but never copy.
#include <cstddef>
#include <functional>
#include <glad/gl.h>
#include <utility>

namespace irad::gl {

enum class Kind { Buffer, VertexArray, Texture, Framebuffer, Renderbuffer, Program, Shader };

template <Kind K>
class Object {
public:
  Object() = default;
  Object(const GladGLContext& api, GLuint name) : api_(&api), name_(name) {}
  ~Object() { reset(); }
  Object(Object&& o) noexcept
      : api_(std::exchange(o.api_, nullptr)), name_(std::exchange(o.name_, 0u)) {}
  Object& operator=(Object&& o) noexcept {
    if (this != &o) {
      reset();
      api_ = std::exchange(o.api_, nullptr);
      name_ = std::exchange(o.name_, 0u);
    }
    return *this;
  }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;

  GLuint get() const { return name_; }
  explicit operator bool() const { return name_ != 0; }

private:
  void reset() {
    if (!api_ || name_ == 0) return;
    if constexpr (K == Kind::Buffer) api_->DeleteBuffers(1, &name_);
    if constexpr (K == Kind::VertexArray) api_->DeleteVertexArrays(1, &name_);
    if constexpr (K == Kind::Texture) api_->DeleteTextures(1, &name_);
    if constexpr (K == Kind::Framebuffer) api_->DeleteFramebuffers(1, &name_);
    if constexpr (K == Kind::Renderbuffer) api_->DeleteRenderbuffers(1, &name_);
    if constexpr (K == Kind::Program) api_->DeleteProgram(name_);
    if constexpr (K == Kind::Shader) api_->DeleteShader(name_);
    name_ = 0;
  }
  const GladGLContext* api_ = nullptr;
  GLuint name_ = 0;
};

using Buffer = Object<Kind::Buffer>;
using VertexArray = Object<Kind::VertexArray>;
using Texture = Object<Kind::Texture>;
using Framebuffer = Object<Kind::Framebuffer>;
using Renderbuffer = Object<Kind::Renderbuffer>;
using Program = Object<Kind::Program>;
using Shader = Object<Kind::Shader>;

// A new name of kind K (not for programs and shaders, which have their own constructors).
template <Kind K>
Object<K> make(const GladGLContext& api) {
  GLuint n = 0;
  if constexpr (K == Kind::Buffer) api.GenBuffers(1, &n);
  if constexpr (K == Kind::VertexArray) api.GenVertexArrays(1, &n);
  if constexpr (K == Kind::Texture) api.GenTextures(1, &n);
  if constexpr (K == Kind::Framebuffer) api.GenFramebuffers(1, &n);
  if constexpr (K == Kind::Renderbuffer) api.GenRenderbuffers(1, &n);
  static_assert(K != Kind::Program && K != Kind::Shader);
  return {api, n};
}
inline Buffer make_buffer(const GladGLContext& api) {
  return make<Kind::Buffer>(api);
}
inline VertexArray make_vertex_array(const GladGLContext& api) {
  return make<Kind::VertexArray>(api);
}
inline Texture make_texture(const GladGLContext& api) {
  return make<Kind::Texture>(api);
}
inline Framebuffer make_framebuffer(const GladGLContext& api) {
  return make<Kind::Framebuffer>(api);
}
inline Renderbuffer make_renderbuffer(const GladGLContext& api) {
  return make<Kind::Renderbuffer>(api);
}

// A float 2D texture of the given size and internal format (with its matching format),
// nearest filtering, left unbound.
inline Texture make_float_texture(const GladGLContext& api, int width, int height,
                                  GLint internal = GL_RGBA32F, GLenum format = GL_RGBA) {
  Texture t = make_texture(api);
  api.BindTexture(GL_TEXTURE_2D, t.get());
  api.TexImage2D(GL_TEXTURE_2D, 0, internal, width, height, 0, format, GL_FLOAT, nullptr);
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  api.BindTexture(GL_TEXTURE_2D, 0);
  return t;
}

// An RG16F one: the batched shadow maps' distance gradients (raster/glsl/cube_glsl.h).
inline Texture make_gradient_texture(const GladGLContext& api, int width, int height) {
  return make_float_texture(api, width, height, GL_RG16F, GL_RG);
}

// Gives the buffer bound to `target` a new store of `bytes` (`usage` as glBufferData's) that
// fill(storage) writes through a write-only mapping: the data is never copied in the process.
// Throws irad::Error naming `what` when the store cannot be mapped or was lost while mapped;
// what fill throws passes on, the buffer unmapped.
void fill_buffer(const GladGLContext& api, GLenum target, std::size_t bytes, GLenum usage,
                 const std::function<void(void*)>& fill, const char* what);
// Writes bytes [offset, offset + bytes) of `buffer`'s existing store through fill(storage), a
// write-only mapping of that range alone, unsynchronised: the range must be one no draw has
// read or is reading (a part not yet written). Binds `buffer` to GL_COPY_WRITE_BUFFER (no VAO
// state changes), unbinds it after. Throws as fill_buffer.
void fill_buffer_range(const GladGLContext& api, GLuint buffer, std::size_t offset,
                       std::size_t bytes, const std::function<void(void*)>& fill, const char* what);

// Throws irad::Error naming `what` unless the bound draw framebuffer is complete.
void check_framebuffer(const GladGLContext& api, const char* what);

// A DEPTH_COMPONENT32F 2D texture of the given size, nearest filtering, no comparison (read as
// a value by texelFetch), left unbound: the shadow atlases' storage.
inline Texture make_depth_texture(const GladGLContext& api, int width, int height) {
  Texture t = make_texture(api);
  api.BindTexture(GL_TEXTURE_2D, t.get());
  api.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT32F, width, height, 0, GL_DEPTH_COMPONENT,
                 GL_FLOAT, nullptr);
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  api.BindTexture(GL_TEXTURE_2D, 0);
  return t;
}

// A framebuffer with `depth` (make_depth_texture) as its only attachment, left bound; throws
// irad::Error naming `what` when incomplete.
inline Framebuffer make_depth_framebuffer(const GladGLContext& api, GLuint depth,
                                          const char* what) {
  Framebuffer f = make_framebuffer(api);
  api.BindFramebuffer(GL_FRAMEBUFFER, f.get());
  api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth, 0);
  api.DrawBuffer(GL_NONE);
  api.ReadBuffer(GL_NONE);
  check_framebuffer(api, what);
  return f;
}

} // namespace irad::gl
