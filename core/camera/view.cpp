#include "core/camera/view.h"

#include <glm/gtc/matrix_transform.hpp>

namespace irad {

View make_view(const Camera& camera, const Bounds& bounds, int width, int height) {
  View v;
  v.width = width;
  v.height = height;
  v.eye = camera.position();
  v.forward = -glm::normalize(glm::vec3(camera.camera_to_world[2]));
  v.orthographic = camera.orthographic;
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
  if (camera.orthographic) {
    const float ymag = camera.ymag, xmag = camera.ymag * aspect;
    v.projection = glm::ortho(-xmag, xmag, -ymag, ymag, near, far);
  } else {
    v.projection = glm::perspective(camera.yfov, aspect, near, far);
  }
  v.inverse_view_projection = glm::inverse(v.projection * v.view);
  return v;
}

CameraRay pixel_ray(const View& view, int px, int py) {
  return image_point_ray(view, static_cast<float>(px) + 0.5f, static_cast<float>(py) + 0.5f);
}

CameraRay image_point_ray(const View& view, float x, float y) {
  const glm::mat4& inv = view.inverse_view_projection;
  const float nx = x / static_cast<float>(view.width) * 2.0f - 1.0f;
  const float ny = 1.0f - y / static_cast<float>(view.height) * 2.0f;
  const glm::vec4 far = inv * glm::vec4(nx, ny, 1.0f, 1.0f);
  if (!view.orthographic) return {view.eye, glm::normalize(glm::vec3(far) / far.w - view.eye)};
  // The point of the near plane under (nx, ny), moved back along -z to the camera plane.
  const glm::vec4 near = inv * glm::vec4(nx, ny, -1.0f, 1.0f);
  return {glm::vec3(near) / near.w - view.znear * view.forward, view.forward};
}

} // namespace irad
