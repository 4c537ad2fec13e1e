// An EGL context without any window: a hardware device through EGL_EXT_platform_device when one
// exists (or the device asked for), else Mesa's surfaceless platform (llvmpipe on a machine with
// no GPU). OpenGL 3.3 core, made current with no surface (EGL_KHR_surfaceless_context): the
// renderer draws into framebuffer objects only.
#include "core/util/error.h"
#include "raster/context/gl_context.h"

#define EGL_NO_X11
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <cstring>
#include <fmt/format.h>
#include <memory>
#include <string>
#include <vector>

namespace irad::gl {

namespace {

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p; p = std::strstr(p + 1, name))
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

template <typename F>
F egl_function(const char* name) {
  return reinterpret_cast<F>(eglGetProcAddress(name));
}

GLADapiproc egl_proc(void* /*user*/, const char* name) {
  return reinterpret_cast<GLADapiproc>(eglGetProcAddress(name));
}

// The devices EGL_EXT_device_enumeration lists, software ones (Mesa's llvmpipe device) last.
std::vector<EGLDeviceEXT> devices(bool& any_hardware) {
  any_hardware = false;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_extension(client, "EGL_EXT_device_enumeration") &&
      !has_extension(client, "EGL_EXT_device_base"))
    return {};
  const auto query = egl_function<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
  const auto query_string = egl_function<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
  EGLint count = 0;
  if (!query || !query(0, nullptr, &count) || count <= 0) return {};
  std::vector<EGLDeviceEXT> all(static_cast<std::size_t>(count));
  query(count, all.data(), &count);
  std::vector<EGLDeviceEXT> hardware, software;
  for (EGLDeviceEXT d : all) {
    const char* ext = query_string ? query_string(d, EGL_EXTENSIONS) : nullptr;
    (has_extension(ext, "EGL_MESA_device_software") ? software : hardware).push_back(d);
  }
  any_hardware = !hardware.empty();
  hardware.insert(hardware.end(), software.begin(), software.end());
  return hardware;
}

// An initialised display and the config its contexts are made with; terminated when the last
// context on it is gone (a shared context holds it too: eglTerminate would end its parent's).
struct EglDisplay {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLConfig config = nullptr;
  std::string platform;
  EglDisplay() = default;
  EglDisplay(const EglDisplay&) = delete;
  EglDisplay& operator=(const EglDisplay&) = delete;
  ~EglDisplay() {
    if (display != EGL_NO_DISPLAY) eglTerminate(display);
  }
};

class EglContext final : public Context {
public:
  explicit EglContext(int device_index) : display_(std::make_shared<EglDisplay>()) {
    open_display(device_index);
    create_context(EGL_NO_CONTEXT);
    if (!eglMakeCurrent(display_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      fail("cannot make the context current");
    if (!gladLoadGLContextUserPtr(&api_, egl_proc, nullptr) || !api_.VERSION_3_3)
      fail("OpenGL 3.3 core functions are missing");
  }
  // A context sharing `share`'s objects and function table, current nowhere.
  explicit EglContext(const EglContext& share) : display_(share.display_) {
    create_context(share.context_);
    api_ = share.api_;
  }
  ~EglContext() override {
    if (context_ == EGL_NO_CONTEXT) return;
    if (eglGetCurrentContext() == context_)
      eglMakeCurrent(display_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_->display, context_);
  }
  std::string backend() const override { return "egl " + display_->platform; }
  void make_current() override {
    if (!eglMakeCurrent(display_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw Error("", "egl " + display_->platform, "cannot make the context current");
  }
  void release() noexcept override {
    eglMakeCurrent(display_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  std::unique_ptr<Context> make_shared() override { return std::make_unique<EglContext>(*this); }

private:
  void open_display(int device_index) {
    const auto get_display =
        egl_function<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
    if (!get_display) throw Error("", "egl", "eglGetPlatformDisplayEXT is missing");
    bool any_hardware = false;
    const std::vector<EGLDeviceEXT> list = devices(any_hardware);
    EglDisplay& d = *display_;
    if (device_index >= 0) {
      if (static_cast<std::size_t>(device_index) >= list.size())
        throw Error("", "--gl-device",
                    fmt::format("no EGL device {} ({} found)", device_index, list.size()));
      d.display = get_display(EGL_PLATFORM_DEVICE_EXT, list[device_index], nullptr);
      d.platform = fmt::format("device {}", device_index);
    } else if (any_hardware) {
      d.display = get_display(EGL_PLATFORM_DEVICE_EXT, list.front(), nullptr);
      d.platform = "device 0";
    } else {
      d.display = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      d.platform = "surfaceless";
    }
    EGLint major = 0, minor = 0;
    if (d.display != EGL_NO_DISPLAY && eglInitialize(d.display, &major, &minor)) return;
    const EGLint code = eglGetError();
    d.display = EGL_NO_DISPLAY; // nothing to terminate
    throw Error("", "egl",
                fmt::format("cannot open the {} display (EGL error 0x{:x})", d.platform, code));
  }

  // An OpenGL 3.3 core context sharing `share`'s objects (EGL_NO_CONTEXT: none); the first one
  // on the display chooses its config.
  void create_context(EGLContext share) {
    EglDisplay& d = *display_;
    if (!d.config) {
      if (!has_extension(eglQueryString(d.display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
        fail("the display lacks EGL_KHR_surfaceless_context");
      const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0,
                                       EGL_NONE};
      EGLint configs = 0;
      if (!eglChooseConfig(d.display, config_attribs, &d.config, 1, &configs) || configs < 1)
        fail("no OpenGL config");
    }
    // The bound API is per thread: the context is made for OpenGL whichever thread asks.
    if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API) failed");
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                      3,
                                      EGL_CONTEXT_MINOR_VERSION,
                                      3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
    context_ = eglCreateContext(d.display, d.config, share, context_attribs);
    if (context_ == EGL_NO_CONTEXT) fail("cannot create an OpenGL 3.3 core context");
  }

  [[noreturn]] void fail(const std::string& what) {
    const EGLint code = eglGetError();
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_->display, context_);
    context_ = EGL_NO_CONTEXT;
    throw Error("", "egl " + display_->platform, fmt::format("{} (EGL error 0x{:x})", what, code));
  }

  std::shared_ptr<EglDisplay> display_;
  EGLContext context_ = EGL_NO_CONTEXT;
};

} // namespace

bool egl_has_hardware_device() {
  bool any_hardware = false;
  devices(any_hardware);
  return any_hardware;
}

std::unique_ptr<Context> create_egl_context(int device_index) {
  return std::make_unique<EglContext>(device_index);
}

} // namespace irad::gl
