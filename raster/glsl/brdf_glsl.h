#pragma once
// The glTF 2.0 BRDF in GLSL (design.md section 1b): the same formulas as core/material/brdf.h
// and core/material/ggx.h, term by term, so that the raster's passes and the CPU estimators
// evaluate one BRDF (tests/test_brdf_glsl.cpp compares them at sampled directions). Inserted
// where a shader's source has the line "#pragma irad_brdf".
//
//   f_r = (1 - m) [(1 - F_d) base/pi + F_d V D] + m F_m V D,  alpha = max(r^2, 1e-3)
//
// D is taken from the unnormalised half vector wo + wi (no cancellation at the peak of a narrow
// lobe); a Lambertian material (m = 0, f0 = f90 = 0) returns base/pi exactly.

namespace irad::gl::shaders {

inline constexpr const char* brdf_glsl = R"(
const float kBrdfPi = 3.14159265358979;
const float kBrdfMinAlpha = 1e-3;

// GGX D from the unnormalised half vector h (its cosine and squared length relative to n).
float brdf_ggx(vec3 n, vec3 h, float alpha) {
  float z = dot(n, h);
  if (z <= 0.0) return 0.0;
  float a2 = alpha * alpha;
  float z2 = z * z, t2 = max(dot(h, h) - z2, 0.0);
  float d = (t2 + a2 * z2) / (t2 + z2);
  return a2 / (kBrdfPi * d * d);
}

// Height-correlated Smith V = G2 / (4 (n.l)(n.v)).
float brdf_visibility(float cos_l, float cos_v, float alpha) {
  if (cos_l <= 0.0 || cos_v <= 0.0) return 0.0;
  float a2 = alpha * alpha;
  float s = cos_l * sqrt(cos_v * cos_v * (1.0 - a2) + a2) +
            cos_v * sqrt(cos_l * cos_l * (1.0 - a2) + a2);
  return s > 0.0 ? 0.5 / s : 0.0;
}

float brdf_schlick_weight(float v_dot_h) {
  float c = clamp(1.0 - abs(v_dot_h), 0.0, 1.0);
  float c2 = c * c;
  return c2 * c2 * c;
}

// f_r(wo, wi) about the unit shading normal n (0 when either direction lies below it).
vec3 brdf_eval(vec3 base, float metallic, float roughness, vec3 f0, float f90, vec3 n, vec3 wo,
               vec3 wi) {
  float cos_o = dot(n, wo), cos_i = dot(n, wi);
  if (cos_o <= 0.0 || cos_i <= 0.0) return vec3(0.0);
  if (metallic == 0.0 && f90 == 0.0 && f0 == vec3(0.0)) return base * (1.0 / kBrdfPi);
  float alpha = max(roughness * roughness, kBrdfMinAlpha);
  vec3 h = normalize(wo + wi);
  float vd = brdf_visibility(cos_i, cos_o, alpha) * brdf_ggx(n, wo + wi, alpha);
  float w = brdf_schlick_weight(dot(wo, h));
  vec3 fd = f0 + (vec3(f90) - f0) * w;
  vec3 fm = base + (1.0 - base) * w;
  vec3 dielectric = (1.0 - fd) * base * (1.0 / kBrdfPi) + fd * vd;
  return (1.0 - metallic) * dielectric + metallic * fm * vd;
}
)";

} // namespace irad::gl::shaders
