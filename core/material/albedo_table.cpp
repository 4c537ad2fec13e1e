#include "core/material/albedo_table.h"

#include "core/material/ggx.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <numbers>
#include <tuple>
#include <utility>

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

// The azimuths phi of a half vector h = (sh cos phi, sh sin phi, ch) (phi from v's plane) that
// reflect v = (st, 0, mu) above the horizon with v.h > 0: |phi| < the returned half-width.
// With v.h = st sh cos phi + mu ch, l.z = 2 (v.h) ch - mu > 0 and v.h > 0 hold where cos phi
// exceeds both mu (1 - 2 ch^2) / (2 st sh ch) and -mu ch / (st sh).
double reflecting_arc(double mu, double st, double ch, double sh) {
  const double pi = std::numbers::pi;
  if (st * sh <= 0.0) return mu * ch > 0.0 && mu * (2.0 * ch * ch - 1.0) > 0.0 ? pi : 0.0;
  const double c =
      std::max(mu * (1.0 - 2.0 * ch * ch) / (2.0 * st * sh * ch), -mu * ch / (st * sh));
  return c >= 1.0 ? 0.0 : c <= -1.0 ? pi : std::acos(c);
}

// (n.h)^2 at the GGX CDF value xi of the density D(h) (n.h): (1 - xi) / (1 + xi (alpha^2 - 1)).
double half_cos2(double xi, double a2) {
  return (1.0 - xi) / (1.0 + xi * (a2 - 1.0));
}

// S and W at one node: midpoint quadrature over half vectors drawn by the density D(h) (n.h)
// through its inverse CDF. With l the reflection of v about h (dl = 4 (v.h) dh),
// V D (n.l) dl / (D (n.h) dh) = 4 V (v.h) (n.l) / (n.h): the peak of D cancels, so the grid
// integrates a smooth function at every roughness. The grid covers only the half vectors that
// reflect above the horizon (reflecting_arc, and xi below the largest such n.h, found by
// bisection): the horizon never cuts a cell, and the integrand goes to 0 at the arc's ends.
void specular_terms(float mu, float alpha, AlbedoTable::Terms& out) {
  const double m = mu, st = std::sqrt(std::max(0.0, 1.0 - m * m)), a2 = double(alpha) * alpha;
  auto arc_at = [&](double xi) {
    const double c2 = half_cos2(xi, a2);
    return reflecting_arc(m, st, std::sqrt(c2), std::sqrt(std::max(0.0, 1.0 - c2)));
  };
  double lo = 0.0, hi = 1.0; // the arc is open at lo; find where it closes
  if (arc_at(1.0 - 1e-12) > 0.0) {
    lo = 1.0;
  } else {
    for (int k = 0; k < 50; ++k) (arc_at(0.5 * (lo + hi)) > 0.0 ? lo : hi) = 0.5 * (lo + hi);
  }
  const double xi_max = lo;
  double s = 0.0, w = 0.0;
  for (int i = 0; i < kGrid; ++i) {
    // xi = xi_max (1 - t^2), dxi = 2 xi_max t dt: points gather toward xi_max, where the
    // horizon's half vectors crowd into a width of about alpha^2.
    const double t = (i + 0.5) / kGrid, xi = xi_max * (1.0 - t * t), dxi = 2.0 * t;
    const double c2 = half_cos2(xi, a2), ch = std::sqrt(c2),
                 sh = std::sqrt(std::max(0.0, 1.0 - c2));
    const double half_width = reflecting_arc(m, st, ch, sh);
    double row_s = 0.0, row_w = 0.0;
    // cos phi at phi_k = -half_width + (k + 1/2) step, by rotating through the step.
    const double step = 2.0 * half_width / kGrid, cs = std::cos(step), ss = std::sin(step);
    double c = std::cos(0.5 * step - half_width), sn = std::sin(0.5 * step - half_width);
    for (int k = 0; k < kGrid;
         ++k, std::tie(c, sn) = std::pair{c * cs - sn * ss, sn * cs + c * ss}) {
      const double vh = st * sh * c + m * ch;
      const double lz = 2.0 * vh * ch - m;
      if (vh <= 0.0 || lz <= 0.0) continue;
      const double term = 4.0 * ggx::visibility(float(lz), mu, alpha) * vh * lz / ch;
      row_s += term;
      row_w += term * ggx::schlick_weight(float(vh));
    }
    const double share = 2.0 * half_width / (2.0 * std::numbers::pi) / kGrid; // dphi / (2 pi)
    s += row_s * share * dxi;
    w += row_w * share * dxi;
  }
  out.s = float(s * xi_max / kGrid);
  out.w = float(w * xi_max / kGrid);
}

// Q at one mu: midpoint quadrature over cosine-distributed l (density (n.l)/pi).
float diffuse_loss(float mu, const Azimuths& phi) {
  const glm::vec3 v = view_at(mu);
  double q = 0.0;
  for (int i = 0; i < kGrid; ++i) {
    const float sin_l = std::sqrt((float(i) + 0.5f) / kGrid),
                cos_l = std::sqrt(1.0f - sin_l * sin_l);
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
      specular_terms(mu_node(i), alpha_of(float(j) / float(kRough - 1)), t);
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
