#include "core/lights/light_sampler.h"

#include "core/sampling/cdf.h"
#include "core/util/error.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace irad {

namespace {

constexpr double pi = std::numbers::pi;

float mean3(const glm::vec3& v) {
  return (v.x + v.y + v.z) / 3.0f;
}

double triangle_power(const Scene& scene, std::size_t t) {
  const Material& m = scene.material_of(t);
  const glm::vec3 le = mean_emission(scene, t);
  const double sides = m.double_sided ? 2.0 : 1.0;
  return sides * pi * triangle_area(scene, t) * mean3(le);
}

// Phi of a punctual light; radius: the scene's bounding sphere (what a directional light covers).
double light_power(const PunctualLight& light, double radius) {
  switch (light.kind) {
  case PunctualLight::Kind::Point:
    return 4.0 * pi * mean3(light.intensity);
  case PunctualLight::Kind::Spot:
    return 2.0 * pi * (1.0 - std::cos(light.outer_cone)) * mean3(light.intensity);
  case PunctualLight::Kind::Directional:
    return pi * radius * radius * mean3(light.intensity);
  }
  return 0.0;
}

// Uniform point on a triangle from the unit square: b1 = v sqrt(u), b2 = ... (area-preserving).
glm::vec2 square_to_triangle(double u, double v) {
  const double su = std::sqrt(u);
  return {static_cast<float>(su * (1.0 - v)), static_cast<float>(su * v)};
}

glm::vec3 uniform_sphere(double u, double v) {
  const double z = 1.0 - 2.0 * u;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.0 * pi * v;
  return {static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
          static_cast<float>(z)};
}

// The point of the disk of radius `radius` around `centre`, perpendicular to unit d, at (u, v):
// uniform in area (r = radius sqrt(u), phi = 2 pi v).
glm::vec3 disk_point(const glm::vec3& centre, const glm::vec3& d, float radius, double u,
                     double v) {
  glm::vec3 t, b;
  orthonormal_basis(d, t, b);
  const double r = radius * std::sqrt(u), phi = 2.0 * pi * v;
  return centre + static_cast<float>(r * std::cos(phi)) * t +
         static_cast<float>(r * std::sin(phi)) * b;
}

glm::vec3 to_world(const glm::vec3& n, const glm::vec3& local) {
  glm::vec3 t, b;
  orthonormal_basis(n, t, b);
  return glm::normalize(local.x * t + local.y * b + local.z * n);
}

} // namespace

void orthonormal_basis(const glm::vec3& n, glm::vec3& t, glm::vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

glm::vec3 cosine_direction(const glm::vec3& n, double u, double v) {
  // sin theta = sqrt(u), so cos theta = sqrt(1 - u); pdf = cos theta / pi.
  const double sin_t = std::sqrt(u);
  const double cos_t = std::sqrt(std::max(0.0, 1.0 - u));
  const double phi = 2.0 * pi * v;
  return to_world(n,
                  glm::vec3(static_cast<float>(sin_t * std::cos(phi)),
                            static_cast<float>(sin_t * std::sin(phi)), static_cast<float>(cos_t)));
}

LightAllocation parse_light_allocation(const std::string& name, const std::string& option) {
  if (name == "power") return LightAllocation::Power;
  if (name == "uniform") return LightAllocation::Uniform;
  throw Error("", option, "must be power or uniform, got '" + name + "'");
}

LightSampler::LightSampler(const Scene& scene, LightAllocation allocation) {
  if (!scene.bounds.empty()) {
    centre_ = scene.bounds.center();
    radius_ = 0.5f * scene.bounds.diagonal();
  }
  for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
    if (!scene.material_of(t).emissive()) continue;
    const double p = triangle_power(scene, t);
    if (p > 0.0) entries_.push_back({static_cast<std::int64_t>(t), p, scene.triangle_material[t]});
  }
  triangle_entries_ = entries_.size();
  for (std::size_t l = 0; l < scene.lights.size(); ++l) {
    const double p = light_power(scene.lights[l], radius_);
    if (p > 0.0)
      entries_.push_back({-static_cast<std::int64_t>(l) - 1, p, scene.materials.size() + l});
  }
  const std::size_t groups = scene.materials.size() + scene.lights.size() + 1;
  if (scene.has_environment()) {
    const double p = pi * double(radius_) * radius_ * scene.environment->mean_radiance_integral();
    if (p > 0.0) {
      entries_.push_back({kEnvironment, p, groups - 1});
      environment_ = scene.environment.get();
    }
  }
  // Selection weights: the power, or under uniform allocation the power within the light divided
  // by the light's power (every light then weighs 1).
  std::vector<double> group_power(groups, 0.0);
  for (const Entry& e : entries_) group_power[e.group] += e.power;
  double sum = 0.0;
  for (const Entry& e : entries_) {
    total_power_ += e.power;
    sum += allocation == LightAllocation::Power ? e.power : e.power / group_power[e.group];
    cdf_.push_back(sum);
  }
  for (double& c : cdf_) c /= sum;
  if (!cdf_.empty()) cdf_.back() = 1.0;
}

LightStart LightSampler::sample(const Scene& scene, double u, double v) const {
  double u_rest = 0.0;
  const std::size_t k = pick_from_cdf(cdf_.data(), cdf_.size(), u, u_rest);
  const double prob = probability(k);

  LightStart s;
  const Entry& e = entries_[k];
  if (e.triangle == kEnvironment) return environment(prob, u_rest, v);
  if (e.triangle >= 0) {
    const auto t = static_cast<std::size_t>(e.triangle);
    const glm::uvec3 tri = scene.triangles[t];
    const glm::vec2 bary = square_to_triangle(u_rest, v);
    const glm::vec3 p0 = scene.positions[tri.x], p1 = scene.positions[tri.y],
                    p2 = scene.positions[tri.z];
    s.position = p0 + bary.x * (p1 - p0) + bary.y * (p2 - p0);
    s.normal = geometric_normal(scene, t);
    s.kind = scene.material_of(t).double_sided ? VplKind::TwoSided : VplKind::Surface;
    s.beta = emission_at(scene, t, bary) * static_cast<float>(triangle_area(scene, t) / prob);
    s.triangle = e.triangle;
    s.bary = bary;
    s.pdf = prob / triangle_area(scene, t);
    return s;
  }
  return punctual(scene.lights[static_cast<std::size_t>(-e.triangle - 1)], prob, u_rest, v);
}

LightStart LightSampler::punctual(const PunctualLight& light, double prob, double u,
                                  double v) const {
  LightStart s;
  s.position = light.position;
  s.normal = light.direction;
  s.beta = light.intensity / static_cast<float>(prob);
  s.pdf = prob;
  switch (light.kind) {
  case PunctualLight::Kind::Point:
    s.kind = VplKind::Point;
    break;
  case PunctualLight::Kind::Spot:
    s.kind = VplKind::Spot;
    s.cos_inner = std::cos(light.inner_cone);
    s.cos_outer = std::cos(light.outer_cone);
    break;
  case PunctualLight::Kind::Directional: {
    // Uniform on the disk of radius R perpendicular to d whose rays along d cover the bounding
    // sphere; the disk lies 1 % of R upstream of the sphere (area density 1 / (pi R^2)).
    s.kind = VplKind::Directional;
    s.position =
        disk_point(centre_ - 1.01f * radius_ * light.direction, light.direction, radius_, u, v);
    s.disk_area = static_cast<float>(pi * radius_ * radius_);
    break;
  }
  }
  return s;
}

LightStart LightSampler::environment(double prob, double u, double v) const {
  const EnvironmentSample e = environment_->sample(u, v);
  LightStart s;
  s.kind = VplKind::Directional;
  s.environment = true;
  s.normal = -e.direction;
  s.position = centre_ + 1.01f * radius_ * e.direction; // the disk's centre; direction() moves it
  s.disk_area = static_cast<float>(pi * radius_ * radius_);
  s.pdf = prob * e.pdf;
  if (s.pdf > 0.0) s.beta = e.radiance / static_cast<float>(s.pdf);
  return s;
}

double LightSampler::environment_pdf(const glm::vec3& w) const {
  return environment_ ? probability(cdf_.size() - 1) * environment_->pdf(w) : 0.0;
}

double LightSampler::area_pdf(const Scene& scene, std::size_t t) const {
  // Triangle entries come first, in increasing triangle order.
  const auto end = entries_.begin() + static_cast<std::ptrdiff_t>(triangle_entries_);
  const auto it =
      std::lower_bound(entries_.begin(), end, static_cast<std::int64_t>(t),
                       [](const Entry& e, std::int64_t key) { return e.triangle < key; });
  if (it == end || it->triangle != static_cast<std::int64_t>(t)) return 0.0;
  return probability(static_cast<std::size_t>(it - entries_.begin())) / triangle_area(scene, t);
}

LightDirection LightSampler::direction(const LightStart& start, double u, double v) const {
  const glm::vec3 o = start.position;
  switch (start.kind) {
  case VplKind::Surface:
    return {cosine_direction(start.normal, u, v), o, static_cast<float>(pi)};
  case VplKind::TwoSided: {
    // v < 1/2 picks the front, else the back; v is rescaled to [0,1) for the azimuth.
    const bool front = v < 0.5;
    const double v2 = front ? 2.0 * v : 2.0 * v - 1.0;
    const glm::vec3 n = front ? start.normal : -start.normal;
    return {cosine_direction(n, u, v2), o, static_cast<float>(2.0 * pi)};
  }
  case VplKind::Point:
    return {uniform_sphere(u, v), o, static_cast<float>(4.0 * pi)};
  case VplKind::Spot: {
    // Uniform in the outer cone: cos theta uniform in [cos_outer, 1]; pdf = 1 / solid angle.
    const double cos_t = 1.0 - u * (1.0 - start.cos_outer);
    const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
    const double phi = 2.0 * pi * v;
    const glm::vec3 d = to_world(start.normal, glm::vec3(static_cast<float>(sin_t * std::cos(phi)),
                                                         static_cast<float>(sin_t * std::sin(phi)),
                                                         static_cast<float>(cos_t)));
    const double solid_angle = 2.0 * pi * (1.0 - start.cos_outer);
    const float falloff = spot_falloff(static_cast<float>(cos_t), start.cos_inner, start.cos_outer);
    return {d, o, static_cast<float>(solid_angle) * falloff};
  }
  case VplKind::Directional: {
    if (!start.environment) return {start.normal, o, start.disk_area};
    return {start.normal, disk_point(o, start.normal, radius_, u, v), start.disk_area};
  }
  }
  return {};
}

} // namespace irad
