#pragma once
// A current OpenGL 3.3+ core context with its glad function table. The renderer draws only into
// framebuffer objects, so no backend needs a window. Backends: OSMesa (llvmpipe on the CPU).
// Internal to raster/: the GL types stay out of the public headers.
#include <glad/gl.h>
#include <memory>
#include <string>

namespace irad::gl {

class Context {
public:
  virtual ~Context() = default;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  const GladGLContext& api() const { return api_; }
  virtual std::string backend() const = 0;
  std::string renderer() const; // GL_RENDERER and GL_VERSION

  // Throws irad::Error naming `where` when glGetError reports an error.
  void check(const char* where) const;

protected:
  Context() = default;
  GladGLContext api_{};
};

std::unique_ptr<Context> create_osmesa_context();

} // namespace irad::gl
