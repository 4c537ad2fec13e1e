#pragma once
// The camera's view and projection for an image of a given size. Near and far planes are fitted
// to the scene's bounds (never absolute lengths), so a scene renders the same at any scale.
#include "core/scene/bounds.h"
#include "core/scene/scene.h"

#include <glm/glm.hpp>

namespace irad {

struct View {
  glm::mat4 view{1.0f};       // world -> camera (OpenGL convention: looking down -z)
  glm::mat4 projection{1.0f}; // camera -> clip, depth range [-1, 1]
  // (projection * view)^-1, set once by make_view: ray directions need no inverse per pixel.
  glm::mat4 inverse_view_projection{1.0f};
  glm::vec3 eye{0.0f};     // the camera's position (orthographic: the centre of its rectangle)
  glm::vec3 forward{0.0f}; // unit, the camera's -z in the world
  bool orthographic = false;
  int width = 0;
  int height = 0;
  float znear = 0.0f;
  float zfar = 0.0f;
};

// Aspect is width / height of the image (the file's aspectRatio only sets the default size).
// far: the farthest corner of the bounds (plus 1%); near: the file's znear when it is positive and
// below far, else far * 1e-4.
// Orthographic: glm::ortho over [-ymag a, ymag a] x [-ymag, ymag] with a = width / height, the
// image's aspect (glTF: when the image's aspect differs from xmag / ymag, the image wins; the
// height keeps ymag and xmag is taken as ymag * a), with the same near and far (depths along -z,
// so the same fit holds).
View make_view(const Camera& camera, const Bounds& bounds, int width, int height);

// A primary ray: origin + t direction for t in [tmin, ...), direction unit. Perspective: from the
// eye; orthographic: from the camera plane (z = 0 of the camera frame) along -z, so that t is the
// depth and tmin = znear is the near plane for both.
struct CameraRay {
  glm::vec3 origin;
  glm::vec3 direction;
};
// The ray through the centre of pixel (px, py), row 0 at the top: the points the raster shades, so
// ray-traced estimators integrate the same function.
CameraRay pixel_ray(const View& view, int px, int py);
// The ray through image point (x, y) in pixels (y down; pixel (i, j) spans [i, i+1) x [j, j+1),
// its centre at (i + 0.5, j + 0.5)).
CameraRay image_point_ray(const View& view, float x, float y);

} // namespace irad
