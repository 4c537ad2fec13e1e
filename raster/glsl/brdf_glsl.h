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
//
// brdf_albedo_glsl adds the directional albedo a(wo) from core's AlbedoTable uploaded as a
// texture (GpuScene::albedo_table), inserted at "#pragma irad_brdf_albedo" after the BRDF.
#include "raster/context/shader_program.h"

#include <string>

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

// Its diffuse lobe alone, (1 - m)(1 - F_d) base/pi (core/material/brdf.h eval_diffuse).
vec3 brdf_eval_diffuse(vec3 base, float metallic, float roughness, vec3 f0, float f90, vec3 n,
                       vec3 wo, vec3 wi) {
  if (dot(n, wo) <= 0.0 || dot(n, wi) <= 0.0) return vec3(0.0);
  if (metallic == 0.0 && f90 == 0.0 && f0 == vec3(0.0)) return base * (1.0 / kBrdfPi);
  float w = brdf_schlick_weight(dot(wo, normalize(wo + wi)));
  vec3 fd = f0 + (vec3(f90) - f0) * w;
  return (1.0 - metallic) * (1.0 - fd) * base * (1.0 / kBrdfPi);
}

// pi f_r(wo, wi) of a receiver at its normal nf (bent toward wo: brdf_facing_normal), its diffuse
// lobe alone when diffuse_only (the glossy camera pass traces the specular one): what the deferred
// and the per-VPL passes weigh a VPL's light by.
vec3 brdf_receiver(vec3 base, float metallic, float roughness, vec3 f0, float f90, vec3 nf,
                   vec3 wo, vec3 wi, bool diffuse_only) {
  return kBrdfPi * (diffuse_only ? brdf_eval_diffuse(base, metallic, roughness, f0, f90, nf, wo, wi)
                                 : brdf_eval(base, metallic, roughness, f0, f90, nf, wo, wi));
}

// f / a per channel, 0 where a is 0 (a demodulating or normalising albedo).
vec3 brdf_over(vec3 f, vec3 a) {
  return vec3(a.r > 0.0 ? f.r / a.r : 0.0, a.g > 0.0 ? f.g / a.g : 0.0,
              a.b > 0.0 ? f.b / a.b : 0.0);
}

// The unit direction from x toward the camera: u_eye = (its position, 1), or (the direction
// toward it, 0) for an orthographic camera (raster/passes/camera_passes.h eye_uniform).
uniform vec4 u_eye;
vec3 toward_eye(vec3 x) {
  return u_eye.w > 0.0 ? normalize(u_eye.xyz - x) : u_eye.xyz;
}

// The shading normal n bent toward wo just enough that wo lies above it (core/material/brdf.h
// facing_normal).
vec3 brdf_facing_normal(vec3 n, vec3 wo) {
  float c = dot(n, wo);
  if (c >= 1e-3) return n;
  return normalize(n + (1e-3 - c) * wo);
}

)";

// The directional albedo (core/material/brdf.h directional_albedo): the table's S, W, Q at
// (mu, r) bilinear between its nodes as AlbedoTable::at, texel (j, i) holding node (mu_i, r_j).
inline constexpr const char* brdf_albedo_glsl = R"(
uniform sampler2D u_albedo_table;
vec3 brdf_table_terms(float mu, float roughness) {
  ivec2 size = textureSize(u_albedo_table, 0); // (r nodes, mu nodes)
  float x = clamp(mu, 0.0, 1.0) * float(size.y - 1);
  float y = clamp(roughness, 0.0, 1.0) * float(size.x - 1);
  int i = min(int(x), size.y - 2), j = min(int(y), size.x - 2);
  float fx = x - float(i), fy = y - float(j);
  vec3 c00 = texelFetch(u_albedo_table, ivec2(j, i), 0).rgb;
  vec3 c01 = texelFetch(u_albedo_table, ivec2(j + 1, i), 0).rgb;
  vec3 c10 = texelFetch(u_albedo_table, ivec2(j, i + 1), 0).rgb;
  vec3 c11 = texelFetch(u_albedo_table, ivec2(j + 1, i + 1), 0).rgb;
  vec3 a = c00 + (c01 - c00) * fy, b = c10 + (c11 - c10) * fy;
  return a + (b - a) * fx;
}
// a(wo) at n.wo = cos_o: the specular lobe (1 - m)(f0 (S - W) + f90 W) + m (base (S - W) + W)
// plus the diffuse one (1 - m) base (1 - f0 (1 - Q) - f90 Q); base for a Lambertian material.
vec3 brdf_albedo(vec3 base, float metallic, float roughness, vec3 f0, float f90, float cos_o) {
  if (metallic == 0.0 && f90 == 0.0 && f0 == vec3(0.0)) return base;
  vec3 t = brdf_table_terms(cos_o, roughness);
  vec3 dielectric = f0 * (t.x - t.y) + f90 * t.y;
  vec3 metal = base * (t.x - t.y) + t.y;
  vec3 kept = 1.0 - f0 * (1.0 - t.z) - f90 * t.z;
  return ((1.0 - metallic) * dielectric + metallic * metal) + (1.0 - metallic) * base * kept;
}

// core/lights/vpl.h spread_roughness: alpha'^2 = alpha^2 + (spread / 2)^2, at most 1.
float brdf_spread_roughness(float roughness, float spread) {
  float a = max(roughness * roughness, kBrdfMinAlpha);
  return sqrt(sqrt(min(a * a + 0.25 * spread * spread, 1.0)));
}

// A glossy VPL's lobe shape pi f_r,y(incident, w) / a(incident) per channel (0 where a is 0),
// about the VPL's normal ny; spread > 0 widens it to the virtual spherical light's and takes the
// widened lobe's albedo (core/lights/vpl.h vpl_lobe_shape).
vec3 brdf_lobe_shape(vec3 base, float metallic, float roughness, vec3 f0, float f90, vec3 ny,
                     vec3 incident, vec3 w, vec3 albedo, float spread) {
  float widened = spread > 0.0 ? brdf_spread_roughness(roughness, spread) : 0.0;
  if (widened > roughness) {
    roughness = widened;
    albedo = brdf_albedo(base, metallic, roughness, f0, f90, dot(ny, incident));
  }
  return brdf_over(kBrdfPi * brdf_eval(base, metallic, roughness, f0, f90, ny, incident, w),
                   albedo);
}
)";

// `source` with its "#pragma irad_brdf" and "#pragma irad_brdf_albedo" lines (where it has them)
// replaced by brdf_glsl and brdf_albedo_glsl.
inline std::string with_brdf(std::string source) {
  insert_glsl(source, "#pragma irad_brdf\n", brdf_glsl);
  insert_glsl(source, "#pragma irad_brdf_albedo\n", brdf_albedo_glsl);
  return source;
}

} // namespace irad::gl::shaders
