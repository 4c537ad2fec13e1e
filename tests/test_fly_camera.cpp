// The walkthrough window's fly camera (core/camera/fly_camera.h) without a window: key and mouse
// state plus a frame time in, camera out. Expected values are from the contract (speed in scene
// diagonals per second, radians per pixel), not from running the code.
#include "core/camera/fly_camera.h"

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace irad {
namespace IRAD_UNITY_ID {

constexpr float kPi = 3.14159265358979f;

// A level camera at (1, 2, 3) looking down -z, as glTF cameras without rotation do.
Camera level_camera() {
  Camera c;
  c.camera_to_world = glm::translate(glm::mat4(1.0f), {1.0f, 2.0f, 3.0f});
  c.yfov = 0.7f;
  return c;
}

// A camera turned 30 degrees about y and tilted 20 degrees down, with 10 degrees of roll.
Camera rolled_camera() {
  Camera c = level_camera();
  c.camera_to_world = glm::rotate(c.camera_to_world, glm::radians(30.0f), {0, 1, 0});
  c.camera_to_world = glm::rotate(c.camera_to_world, glm::radians(-20.0f), {1, 0, 0});
  c.camera_to_world = glm::rotate(c.camera_to_world, glm::radians(10.0f), {0, 0, 1});
  return c;
}

void expect_near(const glm::vec3& a, const glm::vec3& b, float tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

float elevation(const FlyCamera& fly) {
  return std::asin(fly.forward().y);
}

TEST(FlyCamera, NoInputKeepsTheStartCameraExactly) {
  const Camera start = rolled_camera();
  FlyCamera fly(start, 5.0f);
  for (int i = 0; i < 10; ++i) fly.update({}, 0.1f);
  EXPECT_EQ(fly.camera().camera_to_world, start.camera_to_world); // bit-exact: nothing touched
  EXPECT_EQ(fly.camera().yfov, start.yfov);
}

TEST(FlyCamera, ForwardMovesAlongTheViewBySpeedTimesDiagonal) {
  const Camera start = rolled_camera();
  FlyCamera fly(start, 8.0f); // default speed: 0.25 diagonals per second
  const glm::vec3 f = fly.forward();
  FlyInput in;
  in.forward = true;
  fly.update(in, 0.5f);
  expect_near(fly.position(), start.position() + f * (0.25f * 8.0f * 0.5f), 1e-5f);
  expect_near(fly.forward(), f, 1e-6f); // moving does not turn
  in = {};
  in.back = true;
  fly.update(in, 0.5f);
  expect_near(fly.position(), start.position(), 1e-5f);
}

TEST(FlyCamera, StrafeFollowsTheCameraRightAndUpDownTheWorldUp) {
  const Camera start = rolled_camera();
  FlyCamera fly(start, 1.0f); // 0.25 diagonals/s for 0.4 s: 0.1
  const glm::vec3 r = fly.right();
  FlyInput in;
  in.right = true;
  fly.update(in, 0.4f);
  expect_near(fly.position(), start.position() + 0.1f * r, 1e-5f);
  in = {};
  in.up = true; // the world's +y, whatever the camera's tilt and roll
  fly.update(in, 0.4f);
  expect_near(fly.position(), start.position() + 0.1f * r + glm::vec3(0, 0.1f, 0), 1e-5f);
  in = {};
  in.down = in.left = true;
  fly.update(in, 0.4f);
  // a diagonal is normalised: 0.1 in total, split over -r and -y
  const glm::vec3 d = glm::normalize(-r - glm::vec3(0, 1, 0)) * 0.1f;
  expect_near(fly.position(), start.position() + 0.1f * r + glm::vec3(0, 0.1f, 0) + d, 1e-5f);
}

TEST(FlyCamera, OppositeKeysCancelAndFastMultiplies) {
  const Camera start = level_camera();
  FlyCamera fly(start, 2.0f);
  FlyInput in;
  in.forward = in.back = in.left = in.right = true;
  fly.update(in, 1.0f);
  EXPECT_EQ(fly.position(), start.position());
  in = {};
  in.forward = in.fast = true;
  fly.update(in, 0.1f);
  expect_near(fly.position(), start.position() + glm::vec3(0, 0, -0.25f * 2.0f * 4.0f * 0.1f),
              1e-5f);
}

TEST(FlyCamera, SpeedScalesWithTheSceneAndStallsAreClamped) {
  FlyInput in;
  in.forward = true;
  FlyCamera small(level_camera(), 1.0f), large(level_camera(), 100.0f);
  small.update(in, 0.2f);
  large.update(in, 0.2f);
  const glm::vec3 p0 = level_camera().position();
  EXPECT_NEAR(glm::length(small.position() - p0) * 100.0f, glm::length(large.position() - p0),
              1e-3f);
  FlyCamera stalled(level_camera(), 1.0f); // a 10 s frame moves as far as max_dt = 0.5 s
  stalled.update(in, 10.0f);
  EXPECT_NEAR(glm::length(stalled.position() - p0), 0.25f * 0.5f, 1e-6f);
  FlyCamera odd(level_camera(), 1.0f); // negative and NaN durations move nothing
  odd.update(in, -1.0f);
  odd.update(in, std::nanf(""));
  EXPECT_EQ(odd.position(), p0);
}

TEST(FlyCamera, MouseRightTurnsRightAboutTheWorldUp) {
  FlyCamera fly(level_camera(), 1.0f);
  FlyInput in;
  in.look = {100.0f, 0.0f}; // 100 px * 0.004 rad/px = 0.4 rad to the right
  fly.update(in, 0.0f);
  expect_near(fly.forward(), {std::sin(0.4f), 0.0f, -std::cos(0.4f)}, 1e-5f);
  EXPECT_NEAR(fly.right().y, 0.0f, 1e-6f); // a level camera stays level (no roll)
  expect_near(fly.position(), level_camera().position(), 0.0f);
}

TEST(FlyCamera, MouseDownLooksDownAndPitchIsClamped) {
  FlyCamera fly(level_camera(), 1.0f);
  FlyInput in;
  in.look = {0.0f, 50.0f}; // 0.2 rad down
  fly.update(in, 0.0f);
  EXPECT_NEAR(elevation(fly), -0.2f, 1e-5f);
  in.look = {0.0f, -10000.0f}; // 40 rad up: stops at 89 degrees
  fly.update(in, 0.0f);
  EXPECT_NEAR(elevation(fly), glm::radians(89.0f), 1e-4f);
  EXPECT_LT(fly.forward().z, 0.0f); // not flipped over the top
  in.look = {0.0f, 10000.0f};
  fly.update(in, 0.0f);
  EXPECT_NEAR(elevation(fly), -glm::radians(89.0f), 1e-4f);
}

TEST(FlyCamera, PitchOfARolledCameraChangesTheElevationExactly) {
  FlyCamera fly(rolled_camera(), 1.0f);
  const float e0 = elevation(fly);
  EXPECT_NEAR(e0, glm::radians(-20.0f), 1e-5f);
  FlyInput in;
  in.look = {0.0f, -25.0f}; // 0.1 rad up
  fly.update(in, 0.0f);
  EXPECT_NEAR(elevation(fly), e0 + 0.1f, 1e-5f);
}

TEST(FlyCamera, AFullTurnReturnsAndTheAxesStayOrthonormal) {
  const Camera start = rolled_camera();
  FlyCamera fly(start, 1.0f);
  const glm::vec3 f0 = fly.forward();
  FlyInput in;
  const int steps = 1000; // 2 pi in 1000 small yaws, each renormalised
  in.look = {2.0f * kPi / 0.004f / steps, 0.0f};
  for (int i = 0; i < steps; ++i) fly.update(in, 0.0f);
  expect_near(fly.forward(), f0, 1e-4f);
  const glm::mat3 r(fly.camera().camera_to_world);
  const glm::mat3 rtr = glm::transpose(r) * r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(rtr[i][j], i == j ? 1.0f : 0.0f, 1e-5f);
  EXPECT_NEAR(glm::determinant(r), 1.0f, 1e-5f); // still a rotation, no mirroring
}

} // namespace
} // namespace irad
