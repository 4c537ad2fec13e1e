#pragma once
// The glTF 2.0 metallic-roughness BRDF at one surface point (design.md section 1b): the one place
// the CPU estimators (the walk, the path tracer, rt-vpl) evaluate and sample a surface.
//   f_r = (1 - m) [(1 - F_d) base/pi + F_d V D] + m F_m V D
// F_d = Schlick(f0, f90) (the dielectric's, after KHR_materials_ior and KHR_materials_specular),
// F_m = Schlick(base, 1), D GGX, V height-correlated Smith (core/material/ggx.h), alpha = r^2.
// Directions are world-space unit vectors pointing away from the surface: wo toward the viewer
// (or where the light goes), wi toward the light (or where it came from); f_r is reciprocal in
// them. Both must lie above the shading normal n (cosines > 0), else f_r = 0.
#include <glm/glm.hpp>
#include <optional>

namespace irad {

// What the BRDF needs at a point, textures applied (core/material/surface_material.h).
struct BrdfInputs {
  glm::vec3 base{1.0f};   // base colour, linear
  float metallic = 0.0f;  // m in [0, 1]
  float roughness = 1.0f; // perceptual r in [0, 1]
  glm::vec3 f0{0.0f};     // the dielectric's normal-incidence reflectance
  float f90 = 0.0f;       // the dielectric's grazing reflectance (KHR_materials_specular's s)

  // m = 0 and f0 = f90 = 0: f_r = base/pi exactly.
  bool lambertian() const { return metallic == 0.0f && f90 == 0.0f && f0 == glm::vec3(0.0f); }
};

struct BrdfSample {
  glm::vec3 wi{0.0f};     // world, unit, above n
  glm::vec3 weight{0.0f}; // f_r(wo, wi) (n.wi) / pdf
  float pdf = 0.0f;       // solid-angle density of wi (the mixture of both lobes)
};

class Brdf {
public:
  Brdf(const BrdfInputs& inputs, const glm::vec3& normal);

  // f_r(wo, wi), without the cosine.
  glm::vec3 eval(const glm::vec3& wo, const glm::vec3& wi) const;
  // Its two lobes, f_r = diffuse + specular: (1 - m)(1 - F_d) base/pi, and (1 - m) F_d V D +
  // m F_m V D (0 for a Lambertian material).
  glm::vec3 eval_diffuse(const glm::vec3& wo, const glm::vec3& wi) const;
  glm::vec3 eval_specular(const glm::vec3& wo, const glm::vec3& wi) const;
  // wi from the specular lobe alone (visible-normal GGX): weight = eval_specular (n.wi) / pdf,
  // pdf the visible normals' density of wi. nullopt where sample() gives none, and for a
  // Lambertian material.
  std::optional<BrdfSample> sample_specular(const glm::vec3& wo, float u0, float u1) const;
  // The density of sample()'s wi given wo: p_s pdf_ggx + (1 - p_s) (n.wi)/pi, with p_s the
  // specular lobe's share of the directional albedo at wo; visible-normal GGX (Heitz 2018).
  float pdf(const glm::vec3& wo, const glm::vec3& wi) const;
  // wi given wo from (u0, u1) in [0, 1)^2: u0 < p_s picks the specular lobe and is rescaled to
  // [0, 1), so a stratified pair stays stratified in each lobe. nullopt when wi falls below n or
  // wo lies below n.
  std::optional<BrdfSample> sample(const glm::vec3& wo, float u0, float u1) const;
  // Directional albedo a(wo) = integral of f_r(wo, wi) (n.wi) dwi (core/material/albedo_table.h).
  glm::vec3 albedo(const glm::vec3& wo) const;

  const BrdfInputs& inputs() const { return in_; }
  const glm::vec3& normal() const { return n_; }

private:
  glm::vec3 local(const glm::vec3& w) const {
    return {glm::dot(w, t_), glm::dot(w, b_), glm::dot(w, n_)};
  }
  glm::vec3 world(const glm::vec3& w) const { return w.x * t_ + w.y * b_ + w.z * n_; }
  float specular_share(float cos_o) const;

  BrdfInputs in_;
  float alpha_;
  glm::vec3 n_, t_, b_;
};

// The shading normal n bent just enough toward wo that wo lies above it: n itself when n.wo >=
// 1e-3, else normalize(n + (1e-3 - n.wo) wo). Interpolated and mapped normals can face away from
// a direction that sees the surface (at silhouettes); f_r would be 0 there and the point black.
glm::vec3 facing_normal(const glm::vec3& n, const glm::vec3& wo);

// The directional albedo of `inputs` at n.wo = cos_o, per channel (the lobes' split included).
glm::vec3 directional_albedo(const BrdfInputs& inputs, float cos_o);
// Its cosine-weighted mean over incident directions (the hemispherical albedo): the walk's mean
// albedo of a surface.
glm::vec3 hemispherical_albedo(const BrdfInputs& inputs);

} // namespace irad
