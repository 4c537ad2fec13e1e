#include "core/material/brdf.h"

#include "core/material/albedo_table.h"
#include "core/material/ggx.h"

#include <cmath>
#include <numbers>

namespace irad {

namespace {

constexpr float inv_pi = std::numbers::inv_pi_v<float>;

float mean3(const glm::vec3& v) {
  return (v.x + v.y + v.z) / 3.0f;
}

// The albedo's two lobes from the table's terms (core/material/albedo_table.h):
//   specular: (1 - m) (f0 (S - W) + f90 W) + m (base (S - W) + W)
//   diffuse:  (1 - m) base (1 - f0 (1 - Q) - f90 Q)
struct Lobes {
  glm::vec3 specular, diffuse;
};

Lobes lobes(const BrdfInputs& in, const AlbedoTable::Terms& t) {
  const float m = in.metallic;
  const glm::vec3 dielectric = in.f0 * (t.s - t.w) + in.f90 * t.w;
  const glm::vec3 metal = in.base * (t.s - t.w) + t.w;
  const glm::vec3 kept = 1.0f - in.f0 * (1.0f - t.q) - in.f90 * t.q;
  return {(1.0f - m) * dielectric + m * metal, (1.0f - m) * in.base * kept};
}

} // namespace

glm::vec3 facing_normal(const glm::vec3& n, const glm::vec3& wo) {
  constexpr float kMinCos = 1e-3f;
  const float c = glm::dot(n, wo);
  if (c >= kMinCos) return n;
  return glm::normalize(n + (kMinCos - c) * wo);
}

glm::vec3 directional_albedo(const BrdfInputs& in, float cos_o) {
  if (in.lambertian()) return in.base;
  const Lobes l = lobes(in, AlbedoTable::get().at(cos_o, in.roughness));
  return l.specular + l.diffuse;
}

glm::vec3 hemispherical_albedo(const BrdfInputs& in) {
  if (in.lambertian()) return in.base;
  const Lobes l = lobes(in, AlbedoTable::get().hemispherical(in.roughness));
  return l.specular + l.diffuse;
}

Brdf::Brdf(const BrdfInputs& inputs, const glm::vec3& normal)
    : in_(inputs), alpha_(alpha_of(inputs.roughness)), n_(normal) {
  // Duff et al. 2017, "Building an Orthonormal Basis, Revisited".
  const float sign = std::copysign(1.0f, n_.z);
  const float a = -1.0f / (sign + n_.z);
  const float b = n_.x * n_.y * a;
  t_ = glm::vec3(1.0f + sign * n_.x * n_.x * a, sign * b, -sign * n_.x);
  b_ = glm::vec3(b, sign + n_.y * n_.y * a, -n_.y);
}

glm::vec3 Brdf::eval(const glm::vec3& wo, const glm::vec3& wi) const {
  const float cos_o = glm::dot(n_, wo), cos_i = glm::dot(n_, wi);
  if (cos_o <= 0.0f || cos_i <= 0.0f) return glm::vec3(0.0f);
  if (in_.lambertian()) return in_.base * inv_pi;
  const glm::vec3 h = glm::normalize(wo + wi);
  const float vh = glm::dot(wo, h);
  const float vd =
      ggx::visibility(cos_i, cos_o, alpha_) * ggx::distribution_of(local(wo + wi), alpha_);
  const float w = ggx::schlick_weight(vh);
  const glm::vec3 fd = in_.f0 + (glm::vec3(in_.f90) - in_.f0) * w;
  const glm::vec3 fm = in_.base + (1.0f - in_.base) * w;
  const glm::vec3 dielectric = (1.0f - fd) * in_.base * inv_pi + fd * vd;
  return (1.0f - in_.metallic) * dielectric + in_.metallic * fm * vd;
}

glm::vec3 Brdf::eval_diffuse(const glm::vec3& wo, const glm::vec3& wi) const {
  const float cos_o = glm::dot(n_, wo), cos_i = glm::dot(n_, wi);
  if (cos_o <= 0.0f || cos_i <= 0.0f) return glm::vec3(0.0f);
  if (in_.lambertian()) return in_.base * inv_pi;
  const float w = ggx::schlick_weight(glm::dot(wo, glm::normalize(wo + wi)));
  const glm::vec3 fd = in_.f0 + (glm::vec3(in_.f90) - in_.f0) * w;
  return (1.0f - in_.metallic) * (1.0f - fd) * in_.base * inv_pi;
}

glm::vec3 Brdf::eval_specular(const glm::vec3& wo, const glm::vec3& wi) const {
  const float cos_o = glm::dot(n_, wo), cos_i = glm::dot(n_, wi);
  if (cos_o <= 0.0f || cos_i <= 0.0f || in_.lambertian()) return glm::vec3(0.0f);
  const float vd =
      ggx::visibility(cos_i, cos_o, alpha_) * ggx::distribution_of(local(wo + wi), alpha_);
  const float w = ggx::schlick_weight(glm::dot(wo, glm::normalize(wo + wi)));
  const glm::vec3 fd = in_.f0 + (glm::vec3(in_.f90) - in_.f0) * w;
  const glm::vec3 fm = in_.base + (1.0f - in_.base) * w;
  return ((1.0f - in_.metallic) * fd + in_.metallic * fm) * vd;
}

std::optional<BrdfSample> Brdf::sample_specular(const glm::vec3& wo, float u0, float u1) const {
  const glm::vec3 vo = local(wo);
  if (vo.z <= 0.0f || in_.lambertian()) return std::nullopt;
  const glm::vec3 h = ggx::sample_visible_normal(vo, alpha_, glm::min(u0, 0.99999994f), u1);
  const glm::vec3 wi_local = 2.0f * glm::dot(vo, h) * h - vo;
  if (wi_local.z <= 0.0f) return std::nullopt;
  BrdfSample s;
  s.wi = glm::normalize(world(wi_local));
  s.pdf = ggx::visible_normal_pdf(vo, local(wo + s.wi), alpha_);
  if (!(s.pdf > 0.0f)) return std::nullopt;
  s.weight = eval_specular(wo, s.wi) * (glm::dot(n_, s.wi) / s.pdf);
  return s;
}

float Brdf::specular_share(float cos_o) const {
  if (in_.lambertian()) return 0.0f;
  const Lobes l = lobes(in_, AlbedoTable::get().at(cos_o, in_.roughness));
  const float s = mean3(l.specular), d = mean3(l.diffuse);
  if (!(s + d > 0.0f)) return in_.metallic >= 1.0f ? 1.0f : 0.5f;
  return s / (s + d);
}

float Brdf::pdf(const glm::vec3& wo, const glm::vec3& wi) const {
  const float cos_o = glm::dot(n_, wo), cos_i = glm::dot(n_, wi);
  if (cos_o <= 0.0f || cos_i <= 0.0f) return 0.0f;
  const float ps = specular_share(cos_o);
  float p = (1.0f - ps) * cos_i * inv_pi;
  if (ps > 0.0f) p += ps * ggx::visible_normal_pdf(local(wo), local(wo + wi), alpha_);
  return p;
}

std::optional<BrdfSample> Brdf::sample(const glm::vec3& wo, float u0, float u1) const {
  const glm::vec3 vo = local(wo);
  if (vo.z <= 0.0f) return std::nullopt;
  const float ps = specular_share(vo.z);
  glm::vec3 wi_local;
  if (u0 < ps) {
    const glm::vec3 h = ggx::sample_visible_normal(vo, alpha_, glm::min(u0 / ps, 0.99999994f), u1);
    wi_local = 2.0f * glm::dot(vo, h) * h - vo;
  } else {
    const float u = ps > 0.0f ? glm::min((u0 - ps) / (1.0f - ps), 0.99999994f) : u0;
    const float r = std::sqrt(u), phi = 2.0f * std::numbers::pi_v<float> * u1;
    wi_local = {r * std::cos(phi), r * std::sin(phi), std::sqrt(glm::max(0.0f, 1.0f - u))};
  }
  if (wi_local.z <= 0.0f) return std::nullopt;
  BrdfSample s;
  s.wi = glm::normalize(world(wi_local));
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0.0f)) return std::nullopt;
  s.weight = eval(wo, s.wi) * (glm::dot(n_, s.wi) / s.pdf);
  return s;
}

glm::vec3 Brdf::albedo(const glm::vec3& wo) const {
  return directional_albedo(in_, glm::dot(n_, wo));
}

} // namespace irad
