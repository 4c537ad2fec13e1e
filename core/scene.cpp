#include "core/scene.h"

#include <cmath>

namespace irad {

namespace {

// Texture coordinates at barycentrics (b1, b2): (1 - b1 - b2) uv0 + b1 uv1 + b2 uv2.
glm::vec2 uv_at(const Scene& scene, std::size_t t, glm::vec2 bary) {
  const glm::uvec3& tri = scene.triangles[t];
  return (1.0f - bary.x - bary.y) * scene.uvs[tri.x] + bary.x * scene.uvs[tri.y] +
         bary.y * scene.uvs[tri.z];
}

// factor * texture(uv) when the texture exists and the scene has texture coordinates, else factor.
glm::vec3 textured(const Scene& scene, std::size_t t, glm::vec2 bary, glm::vec3 factor,
                   int texture) {
  if (texture < 0 || std::size_t(texture) >= scene.textures.size() || scene.uvs.empty()) {
    return factor;
  }
  return factor * glm::vec3(scene.textures[std::size_t(texture)].sample(uv_at(scene, t, bary)));
}

// The same rule as textured(), with the texture replaced by its texel mean.
glm::vec3 mean_textured(const Scene& scene, glm::vec3 factor, int texture) {
  if (texture < 0 || std::size_t(texture) >= scene.textures.size() || scene.uvs.empty()) {
    return factor;
  }
  return factor * glm::vec3(scene.textures[std::size_t(texture)].mean());
}

// Edge cross product (p1 - p0) x (p2 - p0): |c| = 2 A, direction = counter-clockwise normal.
glm::dvec3 edge_cross(const Scene& scene, std::size_t t) {
  const glm::uvec3& tri = scene.triangles[t];
  const glm::dvec3 p0(scene.positions[tri.x]);
  return glm::cross(glm::dvec3(scene.positions[tri.y]) - p0,
                    glm::dvec3(scene.positions[tri.z]) - p0);
}

} // namespace

bool Scene::has_emitters() const {
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (material_of(t).emissive() && triangle_area(*this, t) > 0.0f) return true;
  }
  return false;
}

bool Scene::has_specular() const {
  for (const Material& m : materials)
    if (m.specular) return true;
  return false;
}

glm::vec3 albedo_at(const Scene& scene, std::size_t t, glm::vec2 bary) {
  const Material& m = scene.material_of(t);
  return textured(scene, t, bary, m.base_color, m.base_color_texture);
}

glm::vec3 emission_at(const Scene& scene, std::size_t t, glm::vec2 bary) {
  const Material& m = scene.material_of(t);
  return textured(scene, t, bary, m.emission, m.emissive_texture);
}

double mean_albedo(const Scene& scene) {
  double weighted = 0.0;
  double area = 0.0;
  for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
    const Material& m = scene.material_of(t);
    const glm::dvec3 rho(mean_textured(scene, m.base_color, m.base_color_texture));
    const double a = 0.5 * glm::length(edge_cross(scene, t));
    weighted += a * (rho.x + rho.y + rho.z) / 3.0;
    area += a;
  }
  return area > 0.0 ? weighted / area : 0.0;
}

float triangle_area(const Scene& scene, std::size_t t) {
  return float(0.5 * glm::length(edge_cross(scene, t)));
}

glm::vec3 geometric_normal(const Scene& scene, std::size_t t) {
  const glm::dvec3 c = edge_cross(scene, t);
  const double len = glm::length(c);
  return len > 0.0 ? glm::vec3(c / len) : glm::vec3(0.0f);
}

SurfacePoint surface_at(const Scene& scene, std::size_t t, glm::vec2 bary) {
  const glm::uvec3& tri = scene.triangles[t];
  const float b0 = 1.0f - bary.x - bary.y;
  SurfacePoint p;
  p.position = b0 * scene.positions[tri.x] + bary.x * scene.positions[tri.y] +
               bary.y * scene.positions[tri.z];
  p.geometric_normal = geometric_normal(scene, t);
  const glm::vec3 n =
      b0 * scene.normals[tri.x] + bary.x * scene.normals[tri.y] + bary.y * scene.normals[tri.z];
  const float length = glm::length(n);
  p.shading_normal = length > 0.0f ? n / length : p.geometric_normal;
  return p;
}

std::optional<glm::mat4> camera_frame_of(const glm::dmat4& world) {
  const glm::dvec3 c1(world[1]);
  const glm::dvec3 c2(world[2]);
  const double l2 = glm::length(c2);
  if (!(l2 > 0.0) || !std::isfinite(l2)) return std::nullopt;
  const glm::dvec3 z = c2 / l2;
  const glm::dvec3 y_perp = c1 - glm::dot(c1, z) * z;
  const double ly = glm::length(y_perp);
  if (!(ly > 1e-12 * glm::length(c1)) || !std::isfinite(ly)) return std::nullopt;
  const glm::dvec3 y = y_perp / ly;
  glm::dmat4 m(glm::dmat3(glm::cross(y, z), y, z));
  m[3] = world[3];
  return glm::mat4(m);
}

} // namespace irad
