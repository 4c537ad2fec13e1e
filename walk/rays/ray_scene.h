#pragma once
// Embree 3 ray queries over an irad::Scene. Owns the device and the scene (RAII); Embree errors
// are routed once through rtcSetDeviceErrorFunction into this object and raised as irad::Error.
// Queries are const and thread-safe.
//
// Alpha (walk/rays/alpha.h): when some material is Mask or Blend, filter functions on the triangle
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
//
// A static scene's triangles are Embree's own view of the scene's positions and triangles (no
// copies) where the positions' storage reaches past the last one (Embree's 16-byte loads):
// the scene given to the constructor must then outlive this object, and its positions and
// triangles stay as they are.
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

// How the static triangles' BVH is built. High (Embree's spatial splits) traces fastest and builds
// slowest; Fast (Embree's Morton builder over its compact triangles, indices into the vertices)
// builds about 3x faster on the 2.1M-triangle sphere box (0.16 against 0.35-0.48 s, 2 cores),
// holds about 30 MiB less there and traces about 10 % slower: the better choice where a render
// traces few rays for its triangles. The hits are the same but for ties between triangles at
// one distance.
enum class BvhQuality { High, Fast };

// One segment origin + t * direction, t in (tmin, tmax), of a batch of queries.
struct RaySegment {
  glm::vec3 origin{0.0f}, direction{0.0f, 0.0f, 1.0f};
  float tmin = 0.0f, tmax = 0.0f;
};

class RayScene {
public:
  explicit RayScene(const Scene& scene, BvhQuality quality = BvhQuality::High);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // Closest hit of origin + t * direction for t in (tmin, tmax); salt: see above.
  std::optional<RayHit> intersect(const glm::vec3& origin, const glm::vec3& direction, float tmin,
                                  float tmax, std::uint64_t salt = 0) const;
  // The closest hits of n segments of any origins: hits[i] the same answer as intersect() for
  // segment i (the alpha filters see the same rays; at a tie between two triangles, either),
  // traced as coherent packets of 8, which pays off where neighbouring segments run close and
  // alike (walk/walls/thin_walls.h: one from each triangle of a mesh, in the mesh's order).
  void intersect(const RaySegment* segments, std::size_t n, std::optional<RayHit>* hits,
                 std::uint64_t salt = 0) const;
  // The same, each segment passing through scene triangle leave[i] as if it were not there (a
  // ray from a point on a triangle that must not find that triangle itself).
  void intersect_leaving(const RaySegment* segments, const std::uint32_t* leave, std::size_t n,
                         std::optional<RayHit>* hits, std::uint64_t salt = 0) const;
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
