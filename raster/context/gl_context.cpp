#include "raster/context/gl_context.h"

#include "core/util/error.h"

#include <cstring>
#include <fmt/format.h>

namespace irad::gl {

std::string Context::renderer() const {
  const auto* r = reinterpret_cast<const char*>(api_.GetString(GL_RENDERER));
  const auto* v = reinterpret_cast<const char*>(api_.GetString(GL_VERSION));
  return fmt::format("{} ({})", r ? r : "?", v ? v : "?");
}

bool Context::cpu_renderer() const {
  const auto* r = reinterpret_cast<const char*>(api_.GetString(GL_RENDERER));
  if (!r) return false;
  const std::string name(r);
  for (const char* cpu : {"llvmpipe", "softpipe", "SwiftShader"})
    if (name.find(cpu) != std::string::npos) return true;
  return false;
}

namespace {

void GLAD_API_PTR on_debug_message(GLenum source, GLenum type, GLuint id, GLenum severity,
                                   GLsizei length, const GLchar* message, const void* user) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
  auto* routing = static_cast<DebugRouting*>(const_cast<void*>(user));
  const bool error = severity == GL_DEBUG_SEVERITY_HIGH || type == GL_DEBUG_TYPE_ERROR;
  const bool first = routing->seen.insert({source, type, id}).second;
  if (!error && !first) return;
  std::string text(message, length > 0 ? static_cast<std::size_t>(length) : std::strlen(message));
  for (char& c : text)
    if (c == '\n') c = ' ';
  routing->sink(fmt::format("OpenGL {} 0x{:x} (id {}): {}{}", error ? "error" : "message", type, id,
                            text, error ? "" : " (its repeats are not shown)"));
}

} // namespace

void Context::route_debug_messages(std::function<void(const std::string&)> sink) {
  if (!api_.KHR_debug || !api_.DebugMessageCallback) return;
  debug_ = DebugRouting{std::move(sink), {}};
  api_.Enable(GL_DEBUG_OUTPUT);
  api_.Enable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
  api_.DebugMessageCallback(on_debug_message, &debug_);
}

void Context::check(const char* where) const {
  const GLenum e = api_.GetError();
  if (e != GL_NO_ERROR) throw Error("", where, fmt::format("OpenGL error 0x{:04x}", e));
}

std::unique_ptr<Context> create_context(GlBackend backend, int device) {
  switch (backend) {
  case GlBackend::Egl:
    return create_egl_context(device);
  case GlBackend::OsMesa:
    if (!osmesa_available())
      throw Error("", "--gl", "this build has no OSMesa (Mesa 25.1 removed it): use --gl egl");
    return create_osmesa_context();
  case GlBackend::Auto:
    break;
  }
  // A GPU when EGL sees one, else the embedded default (OSMesa), else Mesa's surfaceless EGL.
  if (device >= 0 || egl_has_hardware_device()) return create_egl_context(device);
  return osmesa_available() ? create_osmesa_context() : create_egl_context(-1);
}

bool expects_cpu_renderer(GlBackend backend, int device) {
  if (backend == GlBackend::OsMesa) return true;
  if (device >= 0) return false;
  return !egl_has_hardware_device();
}

} // namespace irad::gl
