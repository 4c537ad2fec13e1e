#include "walk/alpha.h"

#include <algorithm>

namespace irad {

float coverage_at(const Scene& scene, std::size_t triangle, glm::vec2 bary) {
  const Material& m = scene.material_of(triangle);
  const glm::uvec3& tri = scene.triangles[triangle];
  const float b0 = 1.0f - bary.x - bary.y;
  float a = m.base_alpha;
  const std::vector<glm::vec2>& uvs = m.base_color_map.texcoord == 1 ? scene.uvs1 : scene.uvs;
  if (m.base_color_texture >= 0 && std::size_t(m.base_color_texture) < scene.textures.size() &&
      !uvs.empty()) {
    const glm::vec2 uv = b0 * uvs[tri.x] + bary.x * uvs[tri.y] + bary.y * uvs[tri.z];
    a *= scene.textures[std::size_t(m.base_color_texture)].sample(m.base_color_map.apply(uv)).a;
  }
  if (!scene.colors.empty())
    a *= b0 * scene.colors[tri.x].a + bary.x * scene.colors[tri.y].a +
         bary.y * scene.colors[tri.z].a;
  return a;
}

bool has_alpha(const Scene& scene) {
  return std::any_of(scene.materials.begin(), scene.materials.end(),
                     [](const Material& m) { return m.alpha_mode != AlphaMode::Opaque; });
}

float presence_at(const Scene& scene, std::size_t triangle, glm::vec2 bary) {
  const Material& m = scene.material_of(triangle);
  switch (m.alpha_mode) {
  case AlphaMode::Opaque:
    return 1.0f;
  case AlphaMode::Mask:
    return coverage_at(scene, triangle, bary) >= m.alpha_cutoff ? 1.0f : 0.0f;
  case AlphaMode::Blend:
    return std::clamp(coverage_at(scene, triangle, bary), 0.0f, 1.0f);
  }
  return 1.0f;
}

float light_presence(const Scene& scene, const LightStart& start) {
  return start.triangle < 0
             ? 1.0f
             : presence_at(scene, static_cast<std::size_t>(start.triangle), start.bary);
}

} // namespace irad
