#include "core/material/ggx.h"

#include <cmath>
#include <numbers>

namespace irad::ggx {

namespace {
constexpr float kPi = std::numbers::pi_v<float>;
} // namespace

float distribution(float cos_h, float alpha) {
  if (cos_h <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha;
  const float d = cos_h * cos_h * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * d * d);
}

float distribution_of(const glm::vec3& h, float alpha) {
  if (h.z <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha;
  const float t2 = h.x * h.x + h.y * h.y, z2 = h.z * h.z;
  const float d = (t2 + a2 * z2) / (t2 + z2);
  return a2 / (kPi * d * d);
}

float visibility(float cos_l, float cos_v, float alpha) {
  if (cos_l <= 0.0f || cos_v <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha;
  const float gv = cos_l * std::sqrt(cos_v * cos_v * (1.0f - a2) + a2);
  const float gl = cos_v * std::sqrt(cos_l * cos_l * (1.0f - a2) + a2);
  const float s = gv + gl;
  return s > 0.0f ? 0.5f / s : 0.0f;
}

float masking(float cos_v, float alpha) {
  if (cos_v <= 0.0f) return 0.0f;
  const float a2 = alpha * alpha;
  return 2.0f * cos_v / (cos_v + std::sqrt(a2 + (1.0f - a2) * cos_v * cos_v));
}

float schlick_weight(float v_dot_h) {
  const float c = glm::clamp(1.0f - std::abs(v_dot_h), 0.0f, 1.0f);
  const float c2 = c * c;
  return c2 * c2 * c;
}

glm::vec3 schlick(const glm::vec3& f0, const glm::vec3& f90, float v_dot_h) {
  return f0 + (f90 - f0) * schlick_weight(v_dot_h);
}

glm::vec3 sample_visible_normal(const glm::vec3& v, float alpha, float u0, float u1) {
  // The hemisphere configuration: stretch v, sample the projected disk of the unit hemisphere
  // seen from it, lift to the hemisphere and unstretch.
  const glm::vec3 vh = glm::normalize(glm::vec3(alpha * v.x, alpha * v.y, v.z));
  const float len2 = vh.x * vh.x + vh.y * vh.y;
  const glm::vec3 t1 =
      len2 > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(len2) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 t2 = glm::cross(vh, t1);
  const float r = std::sqrt(u0);
  const float phi = 2.0f * kPi * u1;
  const float p1 = r * std::cos(phi);
  const float s = 0.5f * (1.0f + vh.z);
  const float p2 = (1.0f - s) * std::sqrt(glm::max(0.0f, 1.0f - p1 * p1)) + s * r * std::sin(phi);
  const glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(glm::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
  return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, glm::max(1e-7f, nh.z)));
}

float visible_normal_pdf(const glm::vec3& v, const glm::vec3& h, float alpha) {
  if (v.z <= 0.0f) return 0.0f;
  return masking(v.z, alpha) * distribution_of(h, alpha) / (4.0f * v.z);
}

} // namespace irad::ggx
