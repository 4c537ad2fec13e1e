#include "core/material/albedo_table.h"

#include "core/material/ggx.h"

#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <numbers>

namespace irad {

namespace {

constexpr int kGrid = 64; // quadrature points per axis
constexpr float kPi = std::numbers::pi_v<float>;

float mu_node(int i) {
  return glm::max(1e-3f, float(i) / float(AlbedoTable::kMu - 1));
}

glm::vec3 view_at(float mu) {
  return {std::sqrt(glm::max(0.0f, 1.0f - mu * mu)), 0.0f, mu};
}

// The quadrature's azimuths (k + 1/2) 2 pi / kGrid as (cos, sin).
struct Azimuths {
  std::array<float, kGrid> c{}, s{};
  Azimuths() {
    for (int k = 0; k < kGrid; ++k) {
      const float phi = 2.0f * kPi * (float(k) + 0.5f) / kGrid;
      c[std::size_t(k)] = std::cos(phi);
      s[std::size_t(k)] = std::sin(phi);
    }
  }
};

// S and W at one node: midpoint quadrature over half vectors drawn by the density D(h) (n.h)
// through its inverse CDF, (n.h)^2 = (1 - xi) / (1 + xi (alpha^2 - 1)). With l the reflection of v
// about h (dl = 4 (v.h) dh), V D (n.l) dl / (D (n.h) dh) = 4 V (v.h) (n.l) / (n.h): the peak of D
// cancels, so the grid integrates a smooth function at every roughness.
void specular_terms(float mu, float alpha, const Azimuths& phi, AlbedoTable::Terms& out) {
  const glm::vec3 v = view_at(mu);
  const float a2 = alpha * alpha;
  double s = 0.0, w = 0.0;
  for (int i = 0; i < kGrid; ++i) {
    const float xi = (float(i) + 0.5f) / kGrid;
    const float c2 = (1.0f - xi) / (1.0f + xi * (a2 - 1.0f));
    const float ch = std::sqrt(c2), sh = std::sqrt(glm::max(0.0f, 1.0f - c2));
    for (std::size_t k = 0; k < kGrid; ++k) {
      const glm::vec3 h(sh * phi.c[k], sh * phi.s[k], ch);
      const float vh = glm::dot(v, h);
      if (vh <= 0.0f) continue;
      const glm::vec3 l = 2.0f * vh * h - v;
      if (l.z <= 0.0f) continue;
      const double term = 4.0 * ggx::visibility(l.z, v.z, alpha) * vh * l.z / ch;
      s += term;
      w += term * ggx::schlick_weight(vh);
    }
  }
  out.s = float(s / (kGrid * kGrid));
  out.w = float(w / (kGrid * kGrid));
}

// Q at one mu: midpoint quadrature over cosine-distributed l (density (n.l)/pi).
float diffuse_loss(float mu, const Azimuths& phi) {
  const glm::vec3 v = view_at(mu);
  double q = 0.0;
  for (int i = 0; i < kGrid; ++i) {
    const float sin_l = std::sqrt((float(i) + 0.5f) / kGrid), cos_l = std::sqrt(1.0f - sin_l * sin_l);
    for (std::size_t k = 0; k < kGrid; ++k) {
      const glm::vec3 l(sin_l * phi.c[k], sin_l * phi.s[k], cos_l);
      q += ggx::schlick_weight(glm::dot(v, glm::normalize(v + l)));
    }
  }
  return float(q / (kGrid * kGrid));
}

} // namespace

AlbedoTable::AlbedoTable() {
  const Azimuths phi;
  for (int i = 0; i < kMu; ++i) {
    const float q = diffuse_loss(mu_node(i), phi);
    for (int j = 0; j < kRough; ++j) {
      Terms& t = cells_[std::size_t(i * kRough + j)];
      specular_terms(mu_node(i), alpha_of(float(j) / float(kRough - 1)), phi, t);
      t.q = q;
    }
  }
  // 2 integral of x(mu) mu dmu by the trapezoid rule over the nodes.
  for (int j = 0; j < kRough; ++j) {
    Terms sum;
    for (int i = 0; i + 1 < kMu; ++i) {
      const float m0 = float(i) / float(kMu - 1), m1 = float(i + 1) / float(kMu - 1);
      const Terms& a = cells_[std::size_t(i * kRough + j)];
      const Terms& b = cells_[std::size_t((i + 1) * kRough + j)];
      const float h = m1 - m0;
      sum.s += h * (a.s * m0 + b.s * m1);
      sum.w += h * (a.w * m0 + b.w * m1);
      sum.q += h * (a.q * m0 + b.q * m1);
    }
    means_[std::size_t(j)] = sum; // 2 * (h/2) (f0 + f1) per interval
  }
}

AlbedoTable::Terms AlbedoTable::at(float mu, float roughness) const {
  const float x = glm::clamp(mu, 0.0f, 1.0f) * float(kMu - 1);
  const float y = glm::clamp(roughness, 0.0f, 1.0f) * float(kRough - 1);
  const int i = glm::min(int(x), kMu - 2), j = glm::min(int(y), kRough - 2);
  const float fx = x - float(i), fy = y - float(j);
  auto cell = [&](int a, int b) { return cells_[std::size_t(a * kRough + b)]; };
  auto lerp = [](const Terms& a, const Terms& b, float t) {
    return Terms{a.s + (b.s - a.s) * t, a.w + (b.w - a.w) * t, a.q + (b.q - a.q) * t};
  };
  return lerp(lerp(cell(i, j), cell(i, j + 1), fy), lerp(cell(i + 1, j), cell(i + 1, j + 1), fy),
              fx);
}

AlbedoTable::Terms AlbedoTable::hemispherical(float roughness) const {
  const float y = glm::clamp(roughness, 0.0f, 1.0f) * float(kRough - 1);
  const int j = glm::min(int(y), kRough - 2);
  const float f = y - float(j);
  const Terms& a = means_[std::size_t(j)];
  const Terms& b = means_[std::size_t(j + 1)];
  return {a.s + (b.s - a.s) * f, a.w + (b.w - a.w) * f, a.q + (b.q - a.q) * f};
}

const AlbedoTable& AlbedoTable::get() {
  static const AlbedoTable table;
  return table;
}

} // namespace irad
