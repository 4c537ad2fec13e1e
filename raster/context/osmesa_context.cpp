// OSMesa: Mesa's off-screen context on llvmpipe, the embedded default. Optional at build time
// (IRAD_HAVE_OSMESA): Mesa 25.1 removed it, and EGL's surfaceless platform then takes its place.
#include "core/util/error.h"
#include "raster/context/gl_context.h"

#ifdef IRAD_HAVE_OSMESA
#include <GL/osmesa.h>
#include <array>

namespace irad::gl {

namespace {

GLADapiproc osmesa_proc(void* /*user*/, const char* name) {
  return reinterpret_cast<GLADapiproc>(OSMesaGetProcAddress(name));
}

// An OSMesa core-profile context made current on a 1x1 dummy colour buffer (all rendering goes
// to framebuffer objects). Owns the context (RAII).
class OsMesaContext final : public Context {
public:
  // share: the context whose objects this one shares (its function table is taken), or nullptr.
  explicit OsMesaContext(const OsMesaContext* share = nullptr) {
    const std::array<int, 13> attribs = {OSMESA_FORMAT,
                                         OSMESA_RGBA,
                                         OSMESA_DEPTH_BITS,
                                         0,
                                         OSMESA_STENCIL_BITS,
                                         0,
                                         OSMESA_PROFILE,
                                         OSMESA_CORE_PROFILE,
                                         OSMESA_CONTEXT_MAJOR_VERSION,
                                         3,
                                         OSMESA_CONTEXT_MINOR_VERSION,
                                         3,
                                         0};
    context_ = OSMesaCreateContextAttribs(attribs.data(), share ? share->context_ : nullptr);
    if (!context_)
      throw Error("", "osmesa", "cannot create an OpenGL 3.3 core context with OSMesa");
    if (share) { // not made current here: the calling thread keeps its own
      api_ = share->api_;
      return;
    }
    if (!OSMesaMakeCurrent(context_, dummy_.data(), GL_UNSIGNED_BYTE, 1, 1)) {
      OSMesaDestroyContext(context_);
      throw Error("", "osmesa", "cannot make the OSMesa context current");
    }
    if (!gladLoadGLContextUserPtr(&api_, osmesa_proc, nullptr) || !api_.VERSION_3_3) {
      OSMesaDestroyContext(context_);
      throw Error("", "osmesa", "OpenGL 3.3 core functions are missing");
    }
  }
  ~OsMesaContext() override { OSMesaDestroyContext(context_); }
  std::string backend() const override { return "osmesa"; }
  void make_current() override {
    if (!OSMesaMakeCurrent(context_, dummy_.data(), GL_UNSIGNED_BYTE, 1, 1))
      throw Error("", "osmesa", "cannot make the OSMesa context current");
  }
  void release() noexcept override { OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0); }
  std::unique_ptr<Context> make_shared() override { return std::make_unique<OsMesaContext>(this); }

private:
  OSMesaContext context_ = nullptr;
  std::array<unsigned char, 4> dummy_{};
};

} // namespace

bool osmesa_available() {
  return true;
}

std::unique_ptr<Context> create_osmesa_context() {
  return std::make_unique<OsMesaContext>();
}

} // namespace irad::gl

#else

namespace irad::gl {

bool osmesa_available() {
  return false;
}

std::unique_ptr<Context> create_osmesa_context() {
  throw Error("", "--gl", "this build has no OSMesa: use --gl egl");
}

} // namespace irad::gl

#endif
