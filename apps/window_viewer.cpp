#include "apps/window_viewer.h"

#include "core/image/image_io.h"
#include "core/util/error.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fmt/format.h>
#include <vector>

#include <GLFW/glfw3.h> // declares the GL 1.x types; irad links no libGL, see PresentGl

namespace irad::apps {

namespace {

// GLFW's description of its last error, on one line.
std::string glfw_error() {
  const char* description = nullptr;
  if (glfwGetError(&description) == GLFW_NO_ERROR || description == nullptr) return "unknown";
  std::string text = description;
  std::replace(text.begin(), text.end(), '\n', ' ');
  return text;
}

// glfwInit ... glfwTerminate.
struct GlfwLibrary {
  GlfwLibrary() {
    if (std::getenv("DISPLAY") == nullptr && std::getenv("WAYLAND_DISPLAY") == nullptr)
      throw Error("", "--window", "no display: DISPLAY and WAYLAND_DISPLAY are unset");
    if (glfwInit() != GLFW_TRUE)
      throw Error("", "--window", "no display: GLFW cannot start: " + glfw_error());
  }
  ~GlfwLibrary() { glfwTerminate(); }
  GlfwLibrary(const GlfwLibrary&) = delete;
  GlfwLibrary& operator=(const GlfwLibrary&) = delete;
};

// The legacy GL functions that present an image, from the window's own context through
// glfwGetProcAddress: nothing here shares the renderer's glad table or context.
struct PresentGl {
  void(GLAPIENTRY* Viewport)(GLint, GLint, GLsizei, GLsizei) = nullptr;
  void(GLAPIENTRY* ClearColor)(GLfloat, GLfloat, GLfloat, GLfloat) = nullptr;
  void(GLAPIENTRY* Clear)(GLbitfield) = nullptr;
  void(GLAPIENTRY* PixelStorei)(GLenum, GLint) = nullptr;
  void(GLAPIENTRY* WindowPos2i)(GLint, GLint) = nullptr; // GL 1.4 (compatibility profile)
  void(GLAPIENTRY* PixelZoom)(GLfloat, GLfloat) = nullptr;
  void(GLAPIENTRY* DrawPixels)(GLsizei, GLsizei, GLenum, GLenum, const void*) = nullptr;
  void(GLAPIENTRY* ReadBuffer)(GLenum) = nullptr;
  void(GLAPIENTRY* ReadPixels)(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void*) = nullptr;
  GLenum(GLAPIENTRY* GetError)() = nullptr;

  template <typename F>
  static void load(F& f, const char* name) {
    f = reinterpret_cast<F>(glfwGetProcAddress(name));
    if (f == nullptr) throw Error("", "--window", fmt::format("the window's GL lacks {}", name));
  }
  void load_all() {
    load(Viewport, "glViewport");
    load(ClearColor, "glClearColor");
    load(Clear, "glClear");
    load(PixelStorei, "glPixelStorei");
    load(WindowPos2i, "glWindowPos2i");
    load(PixelZoom, "glPixelZoom");
    load(DrawPixels, "glDrawPixels");
    load(ReadBuffer, "glReadBuffer");
    load(ReadPixels, "glReadPixels");
    load(GetError, "glGetError");
  }
};

// The window's context is current exactly while one of these lives.
struct CurrentWindow {
  explicit CurrentWindow(GLFWwindow* w) { glfwMakeContextCurrent(w); }
  ~CurrentWindow() { glfwMakeContextCurrent(nullptr); }
  CurrentWindow(const CurrentWindow&) = delete;
  CurrentWindow& operator=(const CurrentWindow&) = delete;
};

// 8-bit sRGB RGB rows bottom-up (GL's order), each byte as write_png makes it.
std::vector<std::uint8_t> display_bytes(const Image& image) {
  const int w = image.width(), h = image.height();
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w) * h * 3);
  std::size_t i = 0;
  for (int y = h - 1; y >= 0; --y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        rgb[i++] = static_cast<std::uint8_t>(
            std::lround(255.0f * linear_to_srgb(tone_map(image.at(x, y)[c], {}))));
  return rgb;
}

// The inverse of the sRGB encoding, so that write_png gives the framebuffer's bytes back.
float srgb_to_linear(std::uint8_t byte) {
  const float v = static_cast<float>(byte) / 255.0f;
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

// GL_RGB bytes, bottom-up, to a linear image, top-down.
Image image_from_bytes(const std::vector<std::uint8_t>& rgb, int w, int h) {
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = (static_cast<std::size_t>(h - 1 - y) * w + x) * 3;
      image.at(x, y) = {srgb_to_linear(rgb[i]), srgb_to_linear(rgb[i + 1]),
                        srgb_to_linear(rgb[i + 2]), 1.0f};
    }
  return image;
}

struct Mouse {
  bool dragging = false;
  double x = 0.0, y = 0.0;
};

bool key(GLFWwindow* w, int k) {
  return glfwGetKey(w, k) == GLFW_PRESS;
}

FlyInput read_input(GLFWwindow* w, Mouse& mouse) {
  FlyInput in;
  in.forward = key(w, GLFW_KEY_W) || key(w, GLFW_KEY_UP);
  in.back = key(w, GLFW_KEY_S) || key(w, GLFW_KEY_DOWN);
  in.left = key(w, GLFW_KEY_A) || key(w, GLFW_KEY_LEFT);
  in.right = key(w, GLFW_KEY_D) || key(w, GLFW_KEY_RIGHT);
  in.up = key(w, GLFW_KEY_E) || key(w, GLFW_KEY_PAGE_UP);
  in.down = key(w, GLFW_KEY_Q) || key(w, GLFW_KEY_PAGE_DOWN);
  in.fast = key(w, GLFW_KEY_LEFT_SHIFT) || key(w, GLFW_KEY_RIGHT_SHIFT);
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(w, &x, &y);
  if (glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) {
    if (mouse.dragging)
      in.look = {static_cast<float>(x - mouse.x), static_cast<float>(y - mouse.y)};
    mouse.dragging = true;
  } else {
    mouse.dragging = false;
  }
  mouse.x = x;
  mouse.y = y;
  return in;
}

} // namespace

struct WindowViewer::Impl {
  WindowOptions options;
  GlfwLibrary library;
  GLFWwindow* window = nullptr;
  PresentGl gl;
  Mouse mouse;

  explicit Impl(const WindowOptions& o) : options(o) {
    // A compatibility context of any version (GLFW's defaults) has glDrawPixels.
    glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    window = glfwCreateWindow(o.width, o.height, o.title.c_str(), nullptr, nullptr);
    if (window == nullptr)
      throw Error("", "--window", "no display: cannot open an OpenGL window: " + glfw_error());
    const CurrentWindow current(window);
    glfwSwapInterval(0); // the frame rate is the renderer's, not the monitor's
    gl.load_all();
  }
  ~Impl() {
    if (window != nullptr) glfwDestroyWindow(window);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  // Draws the image scaled to the framebuffer; with `shot`, reads the framebuffer back into it.
  void present(const Image& image, Image* shot);
  void set_title(double fps, const FrameStatus& status);
};

void WindowViewer::Impl::present(const Image& image, Image* shot) {
  const CurrentWindow current(window);
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window, &fw, &fh);
  gl.Viewport(0, 0, fw, fh);
  gl.ClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  gl.Clear(GL_COLOR_BUFFER_BIT);
  if (image.width() > 0 && image.height() > 0) {
    const std::vector<std::uint8_t> rgb = display_bytes(image);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.WindowPos2i(0, 0);
    gl.PixelZoom(static_cast<float>(fw) / static_cast<float>(image.width()),
                 static_cast<float>(fh) / static_cast<float>(image.height()));
    gl.DrawPixels(image.width(), image.height(), GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
  }
  if (shot != nullptr) { // the back buffer, before the swap leaves it undefined
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(fw) * fh * 3);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadBuffer(GL_BACK);
    gl.ReadPixels(0, 0, fw, fh, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    *shot = image_from_bytes(rgb, fw, fh);
  }
  const GLenum error = gl.GetError();
  if (error != GL_NO_ERROR)
    throw Error("", "--window", fmt::format("OpenGL error 0x{:x} while presenting", error));
  glfwSwapBuffers(window);
}

void WindowViewer::Impl::set_title(double fps, const FrameStatus& status) {
  std::string title = fmt::format("{}: {:.1f} fps", options.title, fps);
  if (status) title += ", " + status();
  glfwSetWindowTitle(window, title.c_str());
}

WindowViewer::WindowViewer(const WindowOptions& options) {
  if (options.frames < 0) throw Error("", "--window-frames", "must be >= 0");
  if (!options.screenshot.empty()) image_format_of(options.screenshot);
  impl_ = std::make_unique<Impl>(options);
}

WindowViewer::~WindowViewer() = default;

WindowStats WindowViewer::run(const Camera& start, const Bounds& bounds,
                              const FrameRenderer& render, const FrameStatus& status) {
  Impl& im = *impl_;
  const WindowOptions& o = im.options;
  FlyCamera fly(start, bounds.diagonal(), o.fly);
  WindowStats stats;
  Image last;
  const double t0 = glfwGetTime();
  double previous = t0, title_time = t0;
  int title_frames = 0;
  im.set_title(0.0, status);
  while (!glfwWindowShouldClose(im.window) && (o.frames == 0 || stats.frames < o.frames)) {
    glfwPollEvents();
    if (key(im.window, GLFW_KEY_ESCAPE)) break;
    const double now = glfwGetTime();
    fly.update(read_input(im.window, im.mouse), static_cast<float>(now - previous));
    previous = now;
    last = render(fly.camera(), stats.frames);
    im.present(last, nullptr);
    ++stats.frames;
    ++title_frames;
    const double t = glfwGetTime();
    if (t - title_time >= 0.5 || stats.frames == 1) { // the rate over the last half second
      im.set_title(title_frames / (t - title_time), status);
      title_time = t;
      title_frames = 0;
    }
  }
  stats.seconds = glfwGetTime() - t0;
  if (!o.screenshot.empty() && stats.frames > 0) {
    Image shot;
    im.present(last, &shot); // the last frame once more, read back from the window
    write_image(o.screenshot, shot);
  }
  return stats;
}

} // namespace irad::apps
