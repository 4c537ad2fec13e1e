#pragma once
// The interactive walkthrough window (irad walkthrough SCENE --window): a GLFW window that shows
// the frames a renderer makes for a fly camera the user steers (core/camera/fly_camera.h):
//   W/S or Up/Down: forward/back, A/D or Left/Right: left/right, E/Q or PageUp/PageDown: up/down,
//   Shift: 4x faster, left mouse drag: look around, Esc or closing the window: quit.
// The window only presents: each frame the renderer's callback draws into its own offscreen GL
// context (OSMesa or EGL) and returns a linear float image, which is tone mapped like a PNG
// (clamp, sRGB; core/image/image_io.h) and drawn with the window's own (GLX) context, made current
// only while presenting. The viewer never touches the renderer's context; the renderer makes its
// own current before drawing (RasterRenderer and RingRenderer do on every call).
#include "core/camera/fly_camera.h"
#include "core/image/image.h"
#include "core/scene/bounds.h"
#include "core/scene/scene.h"

#include <functional>
#include <memory>
#include <string>

namespace irad::apps {

// Renders frame `frame` (0, 1, ...) for `camera` at the window's size.
using FrameRenderer = std::function<Image(const Camera& camera, int frame)>;

struct WindowOptions {
  int width = 256, height = 256; // the window's size and the size frames are rendered at
  std::string title = "irad";
  int frames = 0;         // stop after this many frames (0: until Esc or the window is closed)
  std::string screenshot; // .png or .exr: the window's framebuffer after the last frame
  FlySettings fly;
};

// A short text appended to the title after the frame rate, e.g. "64 paths".
using FrameStatus = std::function<std::string()>;

struct WindowStats {
  int frames = 0;
  double seconds = 0.0; // wall clock from the first frame's start to the last frame's end
  double fps() const { return seconds > 0.0 ? frames / seconds : 0.0; }
};

class WindowViewer {
public:
  // Opens the window (not yet showing a frame). Throws irad::Error when there is no display
  // (DISPLAY and WAYLAND_DISPLAY unset, or GLFW cannot initialise or open an OpenGL window).
  explicit WindowViewer(const WindowOptions& options);
  ~WindowViewer();
  WindowViewer(const WindowViewer&) = delete;
  WindowViewer& operator=(const WindowViewer&) = delete;

  // The frame loop: input -> fly camera -> render(camera, frame) -> present, until Esc, the
  // window is closed, or options.frames frames were shown; then the screenshot, if asked for.
  // Movement speed is relative to bounds.diagonal(). The title shows the frame rate and status().
  WindowStats run(const Camera& start, const Bounds& bounds, const FrameRenderer& render,
                  const FrameStatus& status = {});

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace irad::apps
