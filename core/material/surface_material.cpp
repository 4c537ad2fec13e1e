#include "core/material/surface_material.h"

#include <algorithm>
#include <optional>

namespace irad {

namespace {

// f0 of the dielectric before KHR_materials_specular: ((ior - 1)/(ior + 1))^2 (0.04 at 1.5).
float ior_f0(float ior) {
  const float r = (ior - 1.0f) / (ior + 1.0f);
  return r * r;
}

// The texel of one of the material's textures at a point, or 1 (the factor alone) without it.
glm::vec4 texel_or_one(const Scene& scene, std::size_t t, glm::vec2 bary, int texture,
                       const TexCoordMap& map) {
  return texture_at(scene, t, bary, texture, map).value_or(glm::vec4(1.0f));
}

glm::vec4 mean_or_one(const Scene& scene, const std::vector<glm::vec4>& means, int texture,
                      const TexCoordMap& map) {
  if (texture < 0 || std::size_t(texture) >= means.size() || !has_texcoords(scene, map))
    return glm::vec4(1.0f);
  return means[std::size_t(texture)];
}

// The inputs from the material's factors and its texels (mr: metallicRoughness, spec:
// specular's alpha, colour: specular colour).
BrdfInputs combine(const Material& m, const glm::vec3& base, const glm::vec4& mr, float spec,
                   const glm::vec3& colour) {
  BrdfInputs in;
  in.base = base;
  if (m.lambertian()) return in;
  in.metallic = glm::clamp(m.metallic * mr.b, 0.0f, 1.0f);
  in.roughness = glm::clamp(m.roughness * mr.g, 0.0f, 1.0f);
  const float s = glm::clamp(m.specular_factor * spec, 0.0f, 1.0f);
  in.f0 = glm::min(ior_f0(m.ior) * m.specular_color * colour, glm::vec3(1.0f)) * s;
  in.f90 = s;
  return in;
}

} // namespace

BrdfInputs brdf_inputs_at(const Scene& scene, std::size_t t, glm::vec2 bary) {
  const Material& m = scene.material_of(t);
  const glm::vec3 base = albedo_at(scene, t, bary);
  if (m.lambertian()) return combine(m, base, glm::vec4(1.0f), 1.0f, glm::vec3(1.0f));
  return combine(
      m, base, texel_or_one(scene, t, bary, m.metallic_roughness_texture, m.metallic_roughness_map),
      texel_or_one(scene, t, bary, m.specular_texture, m.specular_map).a,
      glm::vec3(texel_or_one(scene, t, bary, m.specular_color_texture, m.specular_color_map)));
}

std::vector<glm::vec4> texture_means(const Scene& scene) {
  std::vector<glm::vec4> means;
  means.reserve(scene.textures.size());
  for (const Texture& texture : scene.textures) means.push_back(texture.mean());
  return means;
}

BrdfInputs mean_brdf_inputs(const Scene& scene, std::size_t t,
                            const std::vector<glm::vec4>& means) {
  const Material& m = scene.material_of(t);
  glm::vec3 base = m.base_color * glm::vec3(mean_or_one(scene, means, m.base_color_texture,
                                                        m.base_color_map));
  if (!scene.colors.empty()) base *= glm::vec3(vertex_color_at(scene, t, glm::vec2(1.0f / 3.0f)));
  return combine(m, base,
                 mean_or_one(scene, means, m.metallic_roughness_texture, m.metallic_roughness_map),
                 mean_or_one(scene, means, m.specular_texture, m.specular_map).a,
                 glm::vec3(mean_or_one(scene, means, m.specular_color_texture, m.specular_color_map)));
}

glm::vec3 mapped_normal(const Scene& scene, std::size_t t, glm::vec2 bary, const glm::vec3& normal) {
  const Material& m = scene.material_of(t);
  if (m.normal_texture < 0 || scene.tangents.empty()) return normal;
  const std::optional<glm::vec4> c = texture_at(scene, t, bary, m.normal_texture, m.normal_map);
  if (!c) return normal;
  const glm::uvec3& tri = scene.triangles[t];
  const float b0 = 1.0f - bary.x - bary.y;
  const glm::vec4 tan4 = b0 * scene.tangents[tri.x] + bary.x * scene.tangents[tri.y] +
                         bary.y * scene.tangents[tri.z];
  glm::vec3 tangent = glm::vec3(tan4) - glm::dot(glm::vec3(tan4), normal) * normal;
  const float len = glm::length(tangent);
  if (!(len > 1e-6f)) return normal;
  tangent /= len;
  const glm::vec3 bitangent = (tan4.w < 0.0f ? -1.0f : 1.0f) * glm::cross(normal, tangent);
  glm::vec3 n = 2.0f * glm::vec3(*c) - 1.0f;
  n.x *= m.normal_scale;
  n.y *= m.normal_scale;
  const glm::vec3 out = n.x * tangent + n.y * bitangent + n.z * normal;
  const float out_len = glm::length(out);
  return out_len > 1e-6f ? out / out_len : normal;
}

} // namespace irad
