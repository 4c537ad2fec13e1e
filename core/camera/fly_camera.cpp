#include "core/camera/fly_camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace irad {

namespace {

constexpr glm::vec3 kUp{0.0f, 1.0f, 0.0f};

float axis_value(bool positive, bool negative) {
  return static_cast<float>(positive) - static_cast<float>(negative);
}

// Rotates the camera's axes (columns 0..2 of camera_to_world) about a world axis through the eye.
void rotate_axes(glm::mat4& camera_to_world, float angle, const glm::vec3& axis) {
  const glm::mat4 r = glm::rotate(glm::mat4(1.0f), angle, axis);
  for (int c = 0; c < 3; ++c) camera_to_world[c] = r * camera_to_world[c];
}

// Gram-Schmidt on the axes, keeping -z (the view direction) exact: turns accumulate rounding.
void orthonormalize(glm::mat4& m) {
  const glm::vec3 z = glm::normalize(glm::vec3(m[2]));
  glm::vec3 x = glm::vec3(m[0]) - glm::dot(glm::vec3(m[0]), z) * z;
  x = glm::normalize(x);
  const glm::vec3 y = glm::cross(z, x);
  m[0] = glm::vec4(x, 0.0f);
  m[1] = glm::vec4(y, 0.0f);
  m[2] = glm::vec4(z, 0.0f);
}

} // namespace

FlyCamera::FlyCamera(const Camera& start, float scene_diagonal, const FlySettings& settings)
    : camera_(start), diagonal_(scene_diagonal > 0.0f ? scene_diagonal : 1.0f),
      settings_(settings) {}

glm::vec3 FlyCamera::forward() const {
  return -glm::normalize(glm::vec3(camera_.camera_to_world[2]));
}

glm::vec3 FlyCamera::right() const {
  return glm::normalize(glm::vec3(camera_.camera_to_world[0]));
}

void FlyCamera::update(const FlyInput& input, float dt) {
  dt = std::isnan(dt) ? 0.0f : std::clamp(dt, 0.0f, settings_.max_dt);
  if (input.look.x != 0.0f || input.look.y != 0.0f) turn(input.look);
  move(input, dt);
}

// Yaw by -x * k about the world's up (mouse right turns right), then pitch by -y * k about the
// horizontal right axis h = forward x up (mouse down looks down), which changes the elevation
// asin(forward.y) by exactly that angle. The elevation is clamped to +-max_pitch, unless the
// start camera was already beyond it (then it may only move back towards the range).
void FlyCamera::turn(glm::vec2 look) {
  const float k = settings_.radians_per_pixel;
  glm::mat4& m = camera_.camera_to_world;
  if (look.x != 0.0f) rotate_axes(m, -look.x * k, kUp);
  if (look.y != 0.0f) {
    const glm::vec3 f = forward();
    const float elevation = std::asin(std::clamp(f.y, -1.0f, 1.0f));
    const float upper = std::max(settings_.max_pitch, elevation);
    const float lower = std::min(-settings_.max_pitch, elevation);
    const float delta = std::clamp(elevation - look.y * k, lower, upper) - elevation;
    glm::vec3 h = glm::cross(f, kUp);
    h = glm::length(h) > 1e-6f ? glm::normalize(h) : right(); // looking straight up or down
    rotate_axes(m, delta, h);
  }
  orthonormalize(m);
}

void FlyCamera::move(const FlyInput& input, float dt) {
  const glm::vec3 direction = forward() * axis_value(input.forward, input.back) +
                              right() * axis_value(input.right, input.left) +
                              kUp * axis_value(input.up, input.down);
  const float length = glm::length(direction);
  if (length == 0.0f || dt == 0.0f) return;
  const float speed =
      settings_.speed * diagonal_ * (input.fast ? settings_.fast_factor : 1.0f); // per second
  const glm::vec3 step = direction / length * speed * dt;
  camera_.camera_to_world[3] += glm::vec4(step, 0.0f);
}

} // namespace irad
