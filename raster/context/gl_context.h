#pragma once
// A current OpenGL 3.3+ core context with its glad function table. The renderer draws only into
// framebuffer objects, so no backend needs a window. Backends: OSMesa (llvmpipe on the CPU, the
// embedded default) and EGL (a GPU through EGL_EXT_platform_device, or Mesa's surfaceless
// platform).
// Internal to raster/: the GL types stay out of the public headers.
#include "raster/context/gl_backend.h"

#include <exception>
#include <functional>
#include <glad/gl.h>
#include <memory>
#include <set>
#include <string>
#include <tuple>

namespace irad::gl {

// Where a context's KHR_debug messages go, and the kinds already told (source, type, id).
struct DebugRouting {
  std::function<void(const std::string&)> sink;
  std::set<std::tuple<GLenum, GLenum, GLuint>> seen;
};

class Context {
public:
  virtual ~Context() = default;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  const GladGLContext& api() const { return api_; }
  virtual std::string backend() const = 0;
  // Makes this context current on the calling thread (another context may have been made
  // current since this one was created).
  virtual void make_current() = 0;
  // Makes no context current on the calling thread.
  virtual void release() noexcept = 0;
  // A new context of the same backend that shares this one's buffers, textures, programs and
  // sync objects (not its framebuffers and vertex arrays), current nowhere: another thread makes
  // it current (raster/context/gl_thread.h). Its function table is this one's: every backend's
  // entry points dispatch to the calling thread's current context. Throws irad::Error.
  virtual std::unique_ptr<Context> make_shared() = 0;
  std::string renderer() const; // GL_RENDERER and GL_VERSION
  // Whether GL_RENDERER is Mesa's CPU rasterizer (llvmpipe, softpipe) or SwiftShader.
  bool cpu_renderer() const;

  // Throws irad::Error naming `where` when glGetError reports an error.
  void check(const char* where) const;

  // Routes the driver's KHR_debug messages (where the extension exists) to `sink`, one line each,
  // synchronously on the rendering thread: every error, the first of every other kind (source,
  // type and id: a driver's performance hint can repeat once per draw); notifications are left
  // out. The sink must outlive the context or be replaced.
  void route_debug_messages(std::function<void(const std::string&)> sink);

protected:
  Context() = default;
  GladGLContext api_{};

private:
  friend class CurrentScope;
  DebugRouting debug_;
  int scopes_ = 0; // CurrentScope nesting depth
};

// The context current for a scope, then none. The renderers' public calls hold one, so they
// leave no context current: another API's context can then be made current on the same thread
// between calls (the walkthrough window's GLX context, apps/window_viewer.cpp; libglvnd refuses a
// GLX context while an EGL one is current: X error BadAccess). Nested scopes of one context keep
// it current until the outermost ends.
class CurrentScope {
public:
  explicit CurrentScope(Context& context) : context_(context) {
    if (context_.scopes_ == 0) context_.make_current();
    ++context_.scopes_;
  }
  ~CurrentScope() {
    if (--context_.scopes_ == 0) context_.release();
  }
  CurrentScope(const CurrentScope&) = delete;
  CurrentScope& operator=(const CurrentScope&) = delete;

private:
  Context& context_;
};

// For a renderer's destructor: makes `context` current so that the GL objects destroyed next are
// deleted in their own context; if that fails they go with the context itself. Never throws.
inline void make_current_for_teardown(Context& context) noexcept {
  try {
    context.make_current();
  } catch (const std::exception&) {
  }
}

// Auto: an EGL hardware device when there is one (or `device` >= 0 asks for one), else OSMesa,
// else EGL surfaceless. Throws irad::Error naming the backend when it cannot be had.
std::unique_ptr<Context> create_context(GlBackend backend, int device = -1);

std::unique_ptr<Context> create_osmesa_context();
bool osmesa_available();
// device < 0: the first hardware device, else Mesa's surfaceless platform.
std::unique_ptr<Context> create_egl_context(int device = -1);
bool egl_has_hardware_device();

// Whether create_context(backend, device) will make a CPU renderer, as far as can be told
// without making a context: OSMesa always, EGL where it sees no hardware device (Mesa's
// surfaceless llvmpipe), never for a device asked for by index.
bool expects_cpu_renderer(GlBackend backend, int device);

} // namespace irad::gl
