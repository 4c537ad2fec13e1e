#pragma once
// Chooses where light paths start: emissive triangles and punctual lights, with the power
//   triangle k: Phi_k = pi * A_k * mean(L_e,k)  (x2 when double-sided),
//   point:      Phi = 4 pi * mean(I),   spot: Phi = 2 pi (1 - cos outer) * mean(I),
//   directional: Phi = pi R^2 * mean(E)  (R: radius of the scene's bounding sphere).
// Allocation (design.md 6.2, "lights by power"): entry k is chosen with probability P(k):
//   Power:   P(k) = Phi_k / Phi  (the default: every light's share of the paths follows its power),
//   Uniform: P(k) = 1/G * Phi_k / Phi_g(k), G lights, a light being an emissive material (its
//            triangles by power within it) or a punctual light (the seed's "one light after the
//            other": each light gets N/G paths whatever its power).
// Either way the estimate stays unbiased: the start divides by P(k).
// A triangle point is uniform on the triangle, so p(y0) = P(k) / A_k and the path starts with
// beta_0 = L_e(y0) / p(y0); a point or spot light starts with beta_0 = I / P(k); a directional
// light starts uniformly on a disk of radius R perpendicular to d just outside the bounding sphere,
// with beta_0 = E / P(k) (its depth-0 VPL is the light at infinity, C(x) of core/lights/vpl.h).
// The environment (core/environment/environment.h) is one more entry, of power
//   Phi_env = pi R^2 * integral of mean(L(w)) dw   (what crosses a disk of radius R from all w):
// its start picks w by the environment's density p(w) and is a directional start travelling
// along d = -w with beta_0 = L(w) / (p(w) P(k)) (an irradiance: its depth-0 VPL is a directional
// VPL, so sum_k C_k(x) estimates rho/pi * integral of L(w) max(0, n.w) V dw); direction() then
// places it uniformly on the disk of radius R perpendicular to d, just outside the bounding
// sphere, with the factor pi R^2 (beta_1 = L(w) pi R^2 / (p(w) P(k))).
#include "core/lights/vpl.h"
#include "core/scene/scene.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <string>
#include <vector>

namespace irad {

enum class LightAllocation { Power, Uniform };
// "power" or "uniform"; throws irad::Error naming `option` otherwise.
LightAllocation parse_light_allocation(const std::string& name, const std::string& option);

struct LightStart {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f}; // emitter normal (front face), or spot axis
  glm::vec3 beta{0.0f};               // beta_0 as above
  VplKind kind = VplKind::Surface;
  float cos_inner = 1.0f, cos_outer = 0.0f; // Spot only
  std::int64_t triangle = -1;               // the emissive triangle, -1 for punctual lights
  glm::vec2 bary{0.0f};                     // triangle only: barycentrics (b1, b2) of position
  float disk_area = 0.0f;                   // Directional only: pi R^2, the start disk's area
  bool environment = false;                 // a start on the environment (see above)
  double pdf = 0.0; // area density p(y0) = P(k) / A_k on a triangle; P(k) for a punctual light
};

// An outgoing direction from a light start, the point the particle leaves from and the factor
// beta_1 / beta_0 = profile / pdf.
struct LightDirection {
  glm::vec3 direction{0.0f};
  glm::vec3 origin{0.0f}; // the start's position; for an environment start, a point on its disk
  float factor = 0.0f;    // 0: the sample carries no light
};

class LightSampler {
public:
  explicit LightSampler(const Scene& scene, LightAllocation allocation = LightAllocation::Power);

  bool empty() const { return cdf_.empty(); }
  double total_power() const { return total_power_; }
  // (u, v) in [0,1)^2: u picks the light by the power CDF and is then reused (rescaled) with v for
  // the point on the chosen triangle.
  LightStart sample(const Scene& scene, double u, double v) const;
  // Direction leaving a start: cosine-distributed around the front normal (factor pi), either
  // side of a two-sided emitter (factor 2 pi), uniform on the sphere (4 pi), in the spot cone, or
  // d itself for a directional light (factor pi R^2: beta_1 = Phi / P(k)); for an environment
  // start (u, v) place the origin on its disk instead.
  LightDirection direction(const LightStart& start, double u, double v) const;
  // p(y) = P(k) / A_k for a point on emissive triangle t (0 when t is not sampled): what sample()
  // gives that point, for multiple importance sampling.
  double area_pdf(const Scene& scene, std::size_t t) const;
  // P(env) p(w): the solid-angle density with which sample() gives an environment start toward
  // the sky along unit w (0 without an environment), for multiple importance sampling.
  double environment_pdf(const glm::vec3& w) const;

private:
  static constexpr std::int64_t kEnvironment = std::numeric_limits<std::int64_t>::min();
  struct Entry {
    std::int64_t triangle; // >= 0: emissive triangle; kEnvironment; else -(light index + 1)
    double power;
    std::size_t group; // uniform allocation's light: the material, or materials + light index
  };
  LightStart punctual(const PunctualLight& light, double prob, double u, double v) const;
  LightStart environment(double prob, double u, double v) const;
  double probability(std::size_t k) const { return cdf_[k] - (k == 0 ? 0.0 : cdf_[k - 1]); }

  std::vector<Entry> entries_; // emissive triangles (increasing index), then punctual lights
  std::size_t triangle_entries_ = 0;
  std::vector<double> cdf_; // inclusive prefix sums / total
  double total_power_ = 0.0;
  glm::vec3 centre_{0.0f}; // bounding sphere of the scene (directional lights)
  float radius_ = 0.0f;
  const Environment* environment_ = nullptr; // the scene's when it is an entry (the last one)
};

// Cosine-distributed unit direction around n: theta = asin(sqrt(u)), phi = 2 pi v (pdf cos/pi).
glm::vec3 cosine_direction(const glm::vec3& n, double u, double v);
// An orthonormal basis (t, b, n) around a unit n (Duff et al. 2017).
void orthonormal_basis(const glm::vec3& n, glm::vec3& t, glm::vec3& b);

} // namespace irad
