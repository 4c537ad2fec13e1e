#pragma once
// The microfacet terms of the glTF 2.0 BRDF (design.md section 1b) in a local frame whose z axis is
// the shading normal n: every direction is a unit vector with z = its cosine to n. alpha = r^2.
#include <glm/glm.hpp>

namespace irad::ggx {

// GGX (Trowbridge-Reitz) normal distribution D(h) = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2).
float distribution(float cos_h, float alpha);

// The same from an unnormalised half vector h = wo + wi in the local frame:
// (n.h)^2 (alpha^2 - 1) + 1 = (h.x^2 + h.y^2 + alpha^2 h.z^2) / |h|^2, which keeps its precision
// at the peak of a narrow lobe (the form above cancels there in single precision: at alpha 1e-3
// it is off by 3x).
float distribution_of(const glm::vec3& h, float alpha);

// Height-correlated Smith visibility V = G2 / (4 (n.l)(n.v)):
//   V = 1 / (2 ((n.l) sqrt((n.v)^2 (1 - alpha^2) + alpha^2) + (n.v) sqrt((n.l)^2 (1 - alpha^2) +
//   alpha^2))); 0 when either cosine is <= 0.
float visibility(float cos_l, float cos_v, float alpha);

// Smith masking G1(v) = 2 (n.v) / ((n.v) + sqrt(alpha^2 + (1 - alpha^2) (n.v)^2)) (the factor of
// the visible-normal distribution).
float masking(float cos_v, float alpha);

// Schlick's Fresnel F = f0 + (f90 - f0) (1 - |v.h|)^5, per channel.
glm::vec3 schlick(const glm::vec3& f0, const glm::vec3& f90, float v_dot_h);
// The Schlick weight (1 - |v.h|)^5.
float schlick_weight(float v_dot_h);

// A half vector h drawn from the distribution of normals visible from v (Heitz 2018, "Sampling
// the GGX Distribution of Visible Normals"), v.z > 0, (u0, u1) in [0, 1)^2. Its density is
// D_v(h) = G1(v) max(0, v.h) D(h) / v.z, so the reflected l = 2 (v.h) h - v has density
// pdf(l) = G1(v) D(h) / (4 v.z).
glm::vec3 sample_visible_normal(const glm::vec3& v, float alpha, float u0, float u1);

// pdf(l) above for the reflection of v about h (h unnormalised, local).
float visible_normal_pdf(const glm::vec3& v, const glm::vec3& h, float alpha);

} // namespace irad::ggx
