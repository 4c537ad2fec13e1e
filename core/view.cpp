#include "core/view.h"

#include <glm/gtc/matrix_transform.hpp>

namespace irad {

View make_view(const Camera& camera, const Bounds& bounds, int width, int height) {
  View v;
  v.width = width;
  v.height = height;
  v.eye = camera.position();
  v.view = glm::inverse(camera.camera_to_world);
  float far = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? bounds.hi.x : bounds.lo.x,
                      (corner & 2) ? bounds.hi.y : bounds.lo.y,
                      (corner & 4) ? bounds.hi.z : bounds.lo.z);
    far = glm::max(far, glm::length(p - v.eye));
  }
  far = glm::max(far * 1.01f, 1e-30f);
  float near = camera.znear > 0.0f && camera.znear < 0.5f * far ? camera.znear : far * 1e-4f;
  v.znear = near;
  v.zfar = far;
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  v.projection = glm::perspective(camera.yfov, aspect, near, far);
  v.inverse_view_projection = glm::inverse(v.projection * v.view);
  return v;
}

glm::vec3 pixel_direction(const View& view, int px, int py) {
  return image_point_direction(view, static_cast<float>(px) + 0.5f, static_cast<float>(py) + 0.5f);
}

glm::vec3 image_point_direction(const View& view, float x, float y) {
  const glm::mat4& inv = view.inverse_view_projection;
  const float nx = x / static_cast<float>(view.width) * 2.0f - 1.0f;
  const float ny = 1.0f - y / static_cast<float>(view.height) * 2.0f;
  const glm::vec4 far = inv * glm::vec4(nx, ny, 1.0f, 1.0f);
  return glm::normalize(glm::vec3(far) / far.w - view.eye);
}

} // namespace irad
