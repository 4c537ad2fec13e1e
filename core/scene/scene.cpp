#include "core/scene/scene.h"

#include "core/material/surface_material.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace irad {

namespace {

// The texture coordinate set `set` (0: uvs, 1: uvs1), or nullptr when the scene lacks it.
const std::vector<glm::vec2>* uv_set(const Scene& scene, int set) {
  const std::vector<glm::vec2>& uvs = set == 1 ? scene.uvs1 : scene.uvs;
  return (set == 0 || set == 1) && !uvs.empty() ? &uvs : nullptr;
}

// Attribute at barycentrics (b1, b2): (1 - b1 - b2) a0 + b1 a1 + b2 a2.
template <class T>
T interpolate(const std::vector<T>& a, const glm::uvec3& tri, glm::vec2 bary) {
  return (1.0f - bary.x - bary.y) * a[tri.x] + bary.x * a[tri.y] + bary.y * a[tri.z];
}

// factor * texture(uv) when the texture exists and the scene has its texture coordinates, else
// factor.
glm::vec3 textured(const Scene& scene, std::size_t t, glm::vec2 bary, glm::vec3 factor, int texture,
                   const TexCoordMap& map) {
  const std::optional<glm::vec4> c = texture_at(scene, t, bary, texture, map);
  return c ? factor * glm::vec3(*c) : factor;
}

// The same rule as textured(), with the texture replaced by its texel mean (a transform moves
// texels around, so the mean stands for the transformed texture as well); `mean` computes it.
template <class Mean>
glm::vec3 mean_textured(const Scene& scene, glm::vec3 factor, int texture, const TexCoordMap& map,
                        Mean&& mean) {
  if (texture < 0 || std::size_t(texture) >= scene.textures.size() || !has_texcoords(scene, map)) {
    return factor;
  }
  return factor * glm::vec3(mean(std::size_t(texture)));
}

// Edge cross product (p1 - p0) x (p2 - p0): |c| = 2 A, direction = counter-clockwise normal.
glm::dvec3 edge_cross(const Scene& scene, std::size_t t) {
  const glm::uvec3& tri = scene.triangles[t];
  const glm::dvec3 p0(scene.positions[tri.x]);
  return glm::cross(glm::dvec3(scene.positions[tri.y]) - p0,
                    glm::dvec3(scene.positions[tri.z]) - p0);
}

} // namespace

bool has_texcoords(const Scene& scene, const TexCoordMap& map) {
  return uv_set(scene, map.texcoord) != nullptr;
}

std::optional<glm::vec4> texture_at(const Scene& scene, std::size_t t, glm::vec2 bary, int texture,
                                    const TexCoordMap& map) {
  const std::vector<glm::vec2>* uvs = uv_set(scene, map.texcoord);
  if (texture < 0 || std::size_t(texture) >= scene.textures.size() || uvs == nullptr) {
    return std::nullopt;
  }
  const glm::vec2 uv = map.apply(interpolate(*uvs, scene.triangles[t], bary));
  return scene.textures[std::size_t(texture)].sample(uv);
}

glm::vec4 vertex_color_at(const Scene& scene, std::size_t t, glm::vec2 bary) {
  if (scene.colors.empty()) return glm::vec4(1.0f);
  return interpolate(scene.colors, scene.triangles[t], bary);
}

bool Scene::has_emitters() const {
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (material_of(t).emissive() && triangle_area(*this, t) > 0.0f) return true;
  }
  return false;
}

glm::vec3 sun_disk_radiance(const PunctualLight& light) {
  if (light.kind != PunctualLight::Kind::Directional || !(light.angular_radius > 0.0f))
    return glm::vec3(0.0f);
  const float s = std::sin(light.angular_radius);
  return light.intensity / (std::numbers::pi_v<float> * s * s);
}

glm::vec3 background_radiance(const Scene& scene, const glm::vec3& w) {
  if (scene.environment && !scene.environment->visible) return glm::vec3(0.0f);
  glm::vec3 l = scene.environment ? scene.environment->radiance(w) : glm::vec3(0.0f);
  for (const PunctualLight& light : scene.lights)
    if (light.angular_radius > 0.0f &&
        glm::dot(w, -light.direction) >= std::cos(light.angular_radius))
      l += sun_disk_radiance(light);
  return l;
}

bool Scene::has_specular() const {
  for (const Material& m : materials)
    if (m.specular) return true;
  return false;
}

bool Scene::all_lambertian() const {
  for (const Material& m : materials)
    if (!m.specular && !m.lambertian()) return false;
  return true;
}

glm::vec3 albedo_at(const Scene& scene, std::size_t t, glm::vec2 bary) {
  const Material& m = scene.material_of(t);
  return textured(scene, t, bary, m.base_color, m.base_color_texture, m.base_color_map) *
         glm::vec3(vertex_color_at(scene, t, bary));
}

glm::vec3 emission_at(const Scene& scene, std::size_t t, glm::vec2 bary) {
  const Material& m = scene.material_of(t);
  return textured(scene, t, bary, m.emission, m.emissive_texture, m.emissive_map);
}

float coverage_at(const Scene& scene, std::size_t t, glm::vec2 bary) {
  const Material& m = scene.material_of(t);
  if (m.alpha_mode == AlphaMode::Opaque) return 1.0f;
  const std::optional<glm::vec4> c =
      texture_at(scene, t, bary, m.base_color_texture, m.base_color_map);
  return m.base_alpha * (c ? c->w : 1.0f) * vertex_color_at(scene, t, bary).w;
}

bool covered(const Material& material, float coverage, float u) {
  switch (material.alpha_mode) {
  case AlphaMode::Opaque:
    return true;
  case AlphaMode::Mask:
    return coverage >= material.alpha_cutoff;
  case AlphaMode::Blend:
    return u < coverage;
  }
  return true;
}

double mean_albedo(const Scene& scene) {
  const std::vector<glm::vec4> means = texture_means(scene); // once per texture
  auto mean = [&means](std::size_t texture) { return means[texture]; };
  const bool coloured = !scene.colors.empty();
  // Per material: its area and, under COLOR_0, the area-weighted sum of its centroid colours,
  // which a Lambertian or mirror albedo scales linearly; its first triangle stands for it where
  // the albedo does not depend on the triangle. (rho = 1 everywhere gives exactly 1.)
  const std::size_t materials = scene.materials.size();
  std::vector<double> area(materials, 0.0);
  std::vector<glm::dvec3> colour_area(materials, glm::dvec3(0.0));
  std::vector<std::size_t> first(materials, scene.triangles.size());
  double weighted = 0.0; // the per-triangle albedos (a BRDF's under COLOR_0)
  for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
    const std::uint32_t k = scene.triangle_material[t];
    const Material& m = scene.materials[k];
    const double a = 0.5 * glm::length(edge_cross(scene, t));
    area[k] += a;
    first[k] = std::min(first[k], t);
    if (!coloured) continue;
    if (m.lambertian() || m.specular) {
      colour_area[k] += a * glm::dvec3(vertex_color_at(scene, t, glm::vec2(1.0f / 3.0f)));
    } else {
      const glm::dvec3 rho(hemispherical_albedo(mean_brdf_inputs(scene, t, means)));
      weighted += a * (rho.x + rho.y + rho.z) / 3.0;
    }
  }
  double total = 0.0;
  for (std::size_t k = 0; k < materials; ++k) {
    if (first[k] == scene.triangles.size()) continue; // unused
    total += area[k];
    const Material& m = scene.materials[k];
    if (m.lambertian() || m.specular) {
      const glm::dvec3 rho(
          mean_textured(scene, m.base_color, m.base_color_texture, m.base_color_map, mean));
      const glm::dvec3 a = coloured ? colour_area[k] : glm::dvec3(area[k]);
      weighted += (rho.x * a.x + rho.y * a.y + rho.z * a.z) / 3.0;
    } else if (!coloured) {
      const glm::dvec3 rho(hemispherical_albedo(mean_brdf_inputs(scene, first[k], means)));
      weighted += area[k] * (rho.x + rho.y + rho.z) / 3.0;
    }
  }
  return total > 0.0 ? weighted / total : 0.0;
}

glm::vec3 mean_emission(const Scene& scene, std::size_t t) {
  const Material& m = scene.material_of(t);
  return mean_textured(scene, m.emission, m.emissive_texture, m.emissive_map,
                       [&scene](std::size_t texture) { return scene.textures[texture].mean(); });
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
  p.shading_normal = mapped_normal(scene, t, bary, p.shading_normal);
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
