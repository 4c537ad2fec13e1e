#pragma once
// Embree 3 ray queries over an irad::Scene. Owns the device and the scene (RAII); Embree errors
// are routed once through rtcSetDeviceErrorFunction into this object and raised as irad::Error.
// Queries are const and thread-safe.
#include "core/scene.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>

namespace irad {

struct RayHit {
  float t = 0.0f;
  std::uint32_t triangle = 0;
  glm::vec2 bary{0.0f}; // weights of vertices 1 and 2
};

class RayScene {
public:
  explicit RayScene(const Scene& scene);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // Closest hit of origin + t * direction for t in (tmin, tmax).
  std::optional<RayHit> intersect(const glm::vec3& origin, const glm::vec3& direction, float tmin,
                                  float tmax) const;
  // Whether anything blocks the open segment origin + t * direction, t in (tmin, tmax).
  bool occluded(const glm::vec3& origin, const glm::vec3& direction, float tmin, float tmax) const;

  // After Animation::pose moved the scene's vertices: refits the moving triangles' BVH (the
  // still ones are untouched). Nothing happens for a static scene. Not thread-safe with queries.
  void update(const Scene& scene);

  // Ray offsets: a fixed fraction of the bounding diagonal (plus float spacing of the scene's
  // coordinates) so that the same scene at any scale behaves the same.
  float epsilon() const { return epsilon_; }

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  float epsilon_ = 0.0f;
};

} // namespace irad
