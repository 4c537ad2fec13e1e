#include "core/lights/vpl.h"

#include <numbers>

namespace irad {

glm::vec3 vpl_lobe_shape(const VplLobe& lobe, const Vpl& v, const glm::vec3& w) {
  glm::vec3 incident = lobe.incident;
  if (v.mirror >= 0) {
    const glm::vec3 n(v.mirror_plane);
    incident -= 2.0f * glm::dot(incident, n) / glm::dot(n, n) * n;
  }
  const glm::vec3 f = Brdf(lobe.material, v.normal).eval(incident, w);
  glm::vec3 out(0.0f);
  for (int c = 0; c < 3; ++c)
    if (lobe.albedo[c] > 0.0f) out[c] = std::numbers::pi_v<float> * f[c] / lobe.albedo[c];
  return out;
}

} // namespace irad
