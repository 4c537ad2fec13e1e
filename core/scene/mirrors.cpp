#include "core/scene/mirrors.h"

#include <cmath>

namespace irad {

namespace {

// Whether triangle t lies in `plane` (its corners within `tolerance` of it).
bool in_plane(const Scene& scene, std::size_t t, const glm::vec4& plane, float tolerance) {
  const glm::uvec3& tri = scene.triangles[t];
  for (int k = 0; k < 3; ++k)
    if (std::abs(plane_distance(plane, scene.positions[tri[k]])) > tolerance) return false;
  return true;
}

glm::vec4 plane_of(const Scene& scene, std::size_t t) {
  const glm::vec3 n = geometric_normal(scene, t);
  return {n, -glm::dot(n, scene.positions[scene.triangles[t].x])};
}

void append_triangle(const Scene& scene, std::size_t t, MirrorPolygon& polygon) {
  const glm::uvec3& tri = scene.triangles[t];
  for (int k = 0; k < 3; ++k) polygon.triangles.push_back(scene.positions[tri[k]]);
}

} // namespace

std::vector<MirrorPolygon> find_mirrors(const Scene& scene) {
  std::vector<MirrorPolygon> out;
  if (!scene.has_specular()) return out;
  // Coplanar within 1e-5 of the scene's diagonal (the ray offsets are of that order).
  const float tolerance = 1e-5f * scene.bounds.diagonal();
  std::vector<std::size_t> polygon_material; // material of out[k]
  for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
    const Material& m = scene.material_of(t);
    if (!m.specular || triangle_area(scene, t) <= 0.0f) continue;
    const std::size_t material = scene.triangle_material[t];
    std::size_t k = 0;
    while (k < out.size() && !(polygon_material[k] == material &&
                               out[k].triangles.size() < 3 * MirrorPolygon::max_triangles &&
                               in_plane(scene, t, out[k].plane, tolerance)))
      ++k;
    if (k == out.size()) {
      out.push_back({plane_of(scene, t), m.base_color, {}});
      polygon_material.push_back(material);
    }
    append_triangle(scene, t, out[k]);
  }
  return out;
}

std::optional<Vpl> mirrored_vpl(const Vpl& vpl, const std::vector<MirrorPolygon>& mirrors,
                                std::size_t index) {
  // A directional light seen in a mirror would light a prism, not a pyramid: not modelled (its
  // direct light by way of a mirror is missing; its particles still reflect off mirrors).
  if (vpl.kind == VplKind::Directional) return std::nullopt;
  const MirrorPolygon& mirror = mirrors[index];
  const float s = plane_distance(mirror.plane, vpl.position);
  if (s == 0.0f ||
      !(mirror.reflectance.x > 0.0f || mirror.reflectance.y > 0.0f || mirror.reflectance.z > 0.0f))
    return std::nullopt;
  if (vpl.kind == VplKind::Surface) { // one-sided: some corner must lie in front of it
    bool reaches = false;
    for (const glm::vec3& c : mirror.triangles)
      reaches = reaches || glm::dot(vpl.normal, c - vpl.position) > 0.0f;
    if (!reaches) return std::nullopt;
  }
  Vpl copy = vpl;
  copy.position = reflect_point(mirror.plane, vpl.position);
  copy.normal = reflect_direction(glm::vec3(mirror.plane), vpl.normal);
  copy.intensity = vpl.intensity * mirror.reflectance;
  copy.mirror = static_cast<std::int32_t>(index);
  copy.mirror_plane = s > 0.0f ? mirror.plane : -mirror.plane;
  return copy;
}

bool inside_polygon(const MirrorPolygon& mirror, const glm::vec3& m) {
  for (std::size_t k = 0; k + 2 < mirror.triangles.size(); k += 3) {
    const glm::vec3 &a = mirror.triangles[k], &b = mirror.triangles[k + 1],
                    &c = mirror.triangles[k + 2];
    const glm::vec3 n = glm::cross(b - a, c - a);
    if (glm::dot(glm::cross(b - a, m - a), n) >= 0.0f &&
        glm::dot(glm::cross(c - b, m - b), n) >= 0.0f &&
        glm::dot(glm::cross(a - c, m - c), n) >= 0.0f)
      return true;
  }
  return false;
}

std::optional<glm::vec3> mirror_crossing(const Vpl& vpl, const MirrorPolygon& mirror,
                                         const glm::vec3& x) {
  const float sx = plane_distance(vpl.mirror_plane, x);
  const float sy = plane_distance(vpl.mirror_plane, vpl.position); // < 0: behind the plane
  if (!(sx > 0.0f) || !(sy < 0.0f)) return std::nullopt;
  const glm::vec3 m = vpl.position + (sy / (sy - sx)) * (x - vpl.position);
  if (!inside_polygon(mirror, m)) return std::nullopt;
  return m;
}

} // namespace irad
