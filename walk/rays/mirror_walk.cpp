#include "walk/rays/mirror_walk.h"

#include <limits>

namespace irad {

std::optional<RayHit> trace_through_mirrors(const Scene& scene, const RayScene& rays,
                                            glm::vec3& origin, glm::vec3& dir,
                                            glm::vec3& throughput, float eps) {
  const float far = std::numeric_limits<float>::infinity();
  for (int bounce = 0; bounce <= max_mirror_bounces; ++bounce) {
    const auto hit = rays.intersect(origin, dir, 0.0f, far);
    if (!hit || !scene.material_of(hit->triangle).specular) return hit;
    if (bounce == max_mirror_bounces) break;
    glm::vec3 n = geometric_normal(scene, hit->triangle);
    if (glm::dot(n, dir) > 0.0f) n = -n; // the side the ray arrives from
    throughput *= scene.material_of(hit->triangle).base_color;
    origin = origin + hit->t * dir + eps * n;
    dir = reflect_direction(n, dir);
  }
  return std::nullopt;
}

void append_mirrored(Vpl vpl, const std::vector<MirrorPolygon>& mirrors, std::vector<Vpl>& out) {
  for (std::size_t k = 0; k < mirrors.size(); ++k)
    if (const auto copy = mirrored_vpl(vpl, mirrors, k)) out.push_back(*copy);
}

bool mirrored_visible(const RayScene& rays, const Vpl& vpl, const MirrorPolygon& mirror,
                      const glm::vec3& x, float eps) {
  const auto m = mirror_crossing(vpl, mirror, x);
  if (!m) return false;
  // m -> x, then m -> y (y the original VPL, the reflection of vpl.position), each stopping eps
  // short of both ends.
  const glm::vec3 y = reflect_point(vpl.mirror_plane, vpl.position);
  for (const glm::vec3& end : {x, y}) {
    const glm::vec3 d = end - *m;
    const float length = glm::length(d);
    if (length > 2.0f * eps && rays.occluded(*m, d / length, eps, length - eps)) return false;
  }
  return true;
}

} // namespace irad
