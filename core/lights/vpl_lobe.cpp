#include "core/lights/vpl.h"

#include "core/material/albedo_table.h"

#include <cmath>
#include <numbers>

namespace irad {

float spread_roughness(float roughness, float spread) {
  const float a = alpha_of(roughness);
  const float a2 = glm::min(a * a + 0.25f * spread * spread, 1.0f);
  return std::sqrt(std::sqrt(a2));
}

glm::vec3 lobe_incident(const VplLobe& lobe, const Vpl& v) {
  glm::vec3 incident = lobe.incident;
  if (v.mirror >= 0) {
    const glm::vec3 n(v.mirror_plane);
    incident -= 2.0f * glm::dot(incident, n) / glm::dot(n, n) * n;
  }
  return incident;
}

glm::vec3 vpl_lobe_shape(const VplLobe& lobe, const Vpl& v, const glm::vec3& w, float spread) {
  const glm::vec3 incident = lobe_incident(lobe, v);
  BrdfInputs material = lobe.material;
  glm::vec3 albedo = lobe.albedo;
  const float widened = spread > 0.0f ? spread_roughness(material.roughness, spread) : 0.0f;
  if (widened > material.roughness) {
    material.roughness = widened;
    albedo = directional_albedo(material, glm::dot(v.normal, incident));
  }
  const glm::vec3 f = Brdf(material, v.normal).eval(incident, w);
  glm::vec3 out(0.0f);
  for (int c = 0; c < 3; ++c)
    if (albedo[c] > 0.0f) out[c] = std::numbers::pi_v<float> * f[c] / albedo[c];
  return out;
}

} // namespace irad
