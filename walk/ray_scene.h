#pragma once
// Embree 3 ray queries over an irad::Scene. Owns the device and the scene (RAII); Embree errors
// are routed once through rtcSetDeviceErrorFunction into this object and raised as irad::Error.
// Queries are const and thread-safe.
//
// Alpha (walk/alpha.h): when some material is Mask or Blend, filter functions on the triangle
// geometries (both of an animated scene) reject a candidate hit unless u < P(x), P the presence
// at the hit, u a uniform number hashed from the ray's identity: the bits of its origin and
// direction, the caller's salt and the scene triangle. A hash, not a counter, so the answer does
// not depend on traversal order, thread or the order of queries: images stay deterministic per
// seed at any thread count, and the same ray asks the same question twice with the same answer
// (the filter may see a candidate more than once). Rays that are not random themselves (camera
// rays through a pixel centre) vary only through the salt: the path tracer passes one per pixel
// and sample, the VPL estimators pass 0 (a Blend surface seen directly is then dithered per pixel,
// the same pixel always seeing the same thing, and the residual gather sees what rt-vpl saw).
// The scene given to the constructor (or to update()) must then outlive this object: the filters
// read its materials, uvs, colours and textures. Without such materials no filter is installed.
#include "core/scene/scene.h"

#include <cstddef>
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

  // Closest hit of origin + t * direction for t in (tmin, tmax); salt: see above.
  std::optional<RayHit> intersect(const glm::vec3& origin, const glm::vec3& direction, float tmin,
                                  float tmax, std::uint64_t salt = 0) const;
  // Whether anything blocks the open segment origin + t * direction, t in (tmin, tmax).
  bool occluded(const glm::vec3& origin, const glm::vec3& direction, float tmin, float tmax,
                std::uint64_t salt = 0) const;
  // The same question for n segments from one origin, origin + t directions[i], t in
  // (tmin, tmax[i]): blocked[i] = whether something lies on segment i. The same answers as n
  // calls of occluded() (the alpha filters see the same rays), traced as packets of 8, which
  // shares Embree's per-query cost: the light rows' and rt-vpl's shadow rays, many from one point.
  void occluded(const glm::vec3& origin, const glm::vec3* directions, const float* tmax,
                std::size_t n, float tmin, bool* blocked, std::uint64_t salt = 0) const;

  // After Animation::pose moved the scene's vertices: refits the moving triangles' BVH (the
  // still ones are untouched). Nothing happens for a static scene. Not thread-safe with queries.
  void update(const Scene& scene);
  // Whether alpha filters are installed (some material is Mask or Blend).
  bool has_alpha() const;

  // Ray offsets: a fixed fraction of the bounding diagonal (plus float spacing of the scene's
  // coordinates) so that the same scene at any scale behaves the same.
  float epsilon() const { return epsilon_; }

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  float epsilon_ = 0.0f;
};

} // namespace irad
