#pragma once
// A fly-through camera controller for the interactive walkthrough (irad walkthrough --window):
// maps the state of the movement keys and the mouse motion of one frame, plus the frame's
// duration, to the next camera. Pure maths, no window system: the window maps its keys to a
// FlyInput (apps/window_viewer.cpp), so the controller is unit-tested on its own.
//
// Conventions: the world's up is +y (glTF). The camera looks down its local -z, right is its
// local +x (as in core/camera/view.h). Movement keys move along the view direction (forward/back),
// the camera's right axis (left/right) and the world's up (up/down); pressed together they are
// normalised, so a diagonal is not faster. Speed is a fraction of the scene's bounding diagonal
// per second, so every scene takes the same time to cross. Mouse motion turns the camera: x about
// the world's up (yaw), y about the horizontal right axis (pitch), with the view direction's
// elevation kept within +-max_pitch. With no input the camera stays exactly the start camera
// (field of view, planes and any roll included).
#include "core/scene/scene.h"

#include <glm/glm.hpp>

namespace irad {

struct FlyInput {
  bool forward = false, back = false, left = false, right = false, up = false, down = false;
  bool fast = false;    // e.g. shift: speed times FlySettings::fast_factor
  glm::vec2 look{0.0f}; // mouse motion while looking, in pixels (x to the right, y downwards)
};

struct FlySettings {
  float speed = 0.25f;              // scene diagonals per second
  float fast_factor = 4.0f;         // speed multiplier while FlyInput::fast
  float radians_per_pixel = 0.004f; // mouse sensitivity
  float max_pitch = 1.5533430f;     // 89 degrees: the view never turns exactly vertical
  float max_dt = 0.5f;              // seconds: a longer frame (a stall) moves as far as this
};

class FlyCamera {
public:
  // `scene_diagonal` is the length that sets the speed (Bounds::diagonal(); 0 is treated as 1).
  FlyCamera(const Camera& start, float scene_diagonal, const FlySettings& settings = {});

  // Advances by dt seconds (clamped to [0, max_dt]; NaN counts as 0) with this input held.
  void update(const FlyInput& input, float dt);

  const Camera& camera() const { return camera_; }
  glm::vec3 position() const { return camera_.position(); }
  glm::vec3 forward() const; // unit view direction
  glm::vec3 right() const;   // unit camera right axis

private:
  void turn(glm::vec2 look);
  void move(const FlyInput& input, float dt);

  Camera camera_;
  float diagonal_;
  FlySettings settings_;
};

} // namespace irad
