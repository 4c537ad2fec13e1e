#pragma once
// The camera's view and projection for an image of a given size. Near and far planes are fitted
// to the scene's bounds (never absolute lengths), so a scene renders the same at any scale.
#include "core/bounds.h"
#include "core/scene.h"

#include <glm/glm.hpp>

namespace irad {

struct View {
  glm::mat4 view{1.0f};       // world -> camera (OpenGL convention: looking down -z)
  glm::mat4 projection{1.0f}; // camera -> clip, depth range [-1, 1]
  // (projection * view)^-1, set once by make_view: ray directions need no inverse per pixel.
  glm::mat4 inverse_view_projection{1.0f};
  glm::vec3 eye{0.0f};
  int width = 0;
  int height = 0;
  float znear = 0.0f;
  float zfar = 0.0f;
};

// Aspect is width / height of the image (the file's aspectRatio only sets the default size).
// far: the farthest corner of the bounds (plus 1%); near: the file's znear when it is positive and
// below far, else far * 1e-4.
View make_view(const Camera& camera, const Bounds& bounds, int width, int height);

// Unit direction of the ray from the eye through the centre of pixel (px, py), row 0 at the top:
// the points the raster shades, so ray-traced estimators integrate the same function.
glm::vec3 pixel_direction(const View& view, int px, int py);
// The direction through image point (x, y) in pixels (y down; pixel (i, j) spans [i, i+1) x
// [j, j+1), its centre at (i + 0.5, j + 0.5)).
glm::vec3 image_point_direction(const View& view, float x, float y);

} // namespace irad
