#include "walk/rays/alpha.h"

#include <algorithm>

namespace irad {

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
