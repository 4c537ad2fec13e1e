#include "walk/estimators/path_tracer.h"

#include "core/lights/light_sampler.h"
#include "core/lights/vpl.h"
#include "core/material/surface_material.h"
#include "core/sampling/rng.h"
#include "core/util/error.h"
#include "core/util/parallel_rows.h"
#include "walk/rays/alpha.h"

#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>
#include <optional>

namespace irad {

namespace {

constexpr float inv_pi = std::numbers::inv_pi_v<float>;

float power_heuristic(double a, double b) {
  const double a2 = a * a, b2 = b * b;
  return a2 + b2 > 0.0 ? static_cast<float>(a2 / (a2 + b2)) : 0.0f;
}

float max3(const glm::vec3& v) {
  return glm::max(v.x, glm::max(v.y, v.z));
}

// A surface hit, with normals turned toward the side the ray arrived from. A material that is
// not Lambertian (Material::lambertian) carries its BRDF; a Lambertian one is albedo/pi.
struct Hit {
  glm::vec3 position, ng, ns, albedo;
  glm::vec3 wo; // unit, toward where the ray came from
  std::uint32_t triangle;
  glm::vec2 bary;
  bool front; // the ray hit the front (counter-clockwise) face
  std::optional<Brdf> brdf;

  // f_r(wo, w) and the solid-angle density with which scattering finds w.
  glm::vec3 f(const glm::vec3& w) const { return brdf ? brdf->eval(wo, w) : albedo * inv_pi; }
  float scatter_pdf(const glm::vec3& w, float cos_w) const {
    return brdf ? brdf->pdf(wo, w) : cos_w * inv_pi;
  }
};

Hit make_hit(const Scene& scene, const RayHit& h, const glm::vec3& origin, const glm::vec3& dir) {
  const SurfacePoint sp = surface_at(scene, h.triangle, h.bary);
  Hit hit;
  hit.position = origin + h.t * dir;
  hit.front = glm::dot(sp.geometric_normal, dir) < 0.0f;
  hit.ng = hit.front ? sp.geometric_normal : -sp.geometric_normal;
  hit.ns = hit.front ? sp.shading_normal : -sp.shading_normal;
  hit.albedo = albedo_at(scene, h.triangle, h.bary);
  hit.triangle = h.triangle;
  hit.bary = h.bary;
  hit.wo = -dir;
  const Material& m = scene.material_of(h.triangle);
  if (!m.lambertian() && !m.specular) {
    const glm::vec3 ns = glm::dot(hit.ns, hit.ng) > 0.0f ? hit.ns : hit.ng;
    hit.brdf.emplace(brdf_inputs_at(scene, h.triangle, h.bary), facing_normal(ns, hit.wo));
  }
  return hit;
}

// Radiance the hit surface emits back along the ray (front face only unless double-sided).
glm::vec3 emitted(const Scene& scene, const Hit& hit) {
  const Material& m = scene.material_of(hit.triangle);
  if (!m.emissive() || (!hit.front && !m.double_sided)) return glm::vec3(0.0f);
  return emission_at(scene, hit.triangle, hit.bary);
}

struct Scatter {
  glm::vec3 direction;
  glm::vec3 weight; // f cos / pdf
  double pdf;
};

std::optional<Scatter> scatter(const Hit& x, Pcg32& rng);

class Tracer {
public:
  Tracer(const Scene& scene, const RayScene& rays, const PathTracerOptions& options)
      : scene_(scene), rays_(rays), options_(options), lights_(scene), eps_(rays.epsilon()) {}

  // salt: the ray queries' salt (walk/rays/ray_scene.h), one per pixel and sample, so that the
  // samples of one pixel, whose camera rays coincide, make independent Blend decisions.
  glm::vec3 radiance(const glm::vec3& eye, const glm::vec3& dir, float tmin, Pcg32& rng,
                     std::uint64_t salt) const;

private:
  glm::vec3 next_event(const Hit& x, Pcg32& rng, std::uint64_t salt) const;
  glm::vec3 directional(const Hit& x, const LightStart& s, std::uint64_t salt) const;
  float emitter_weight(const Hit& y, const glm::vec3& from, double bsdf_pdf) const;
  glm::vec3 escaped(const glm::vec3& dir, int depth, bool specular, double bsdf_pdf) const;

  const Scene& scene_;
  const RayScene& rays_;
  const PathTracerOptions& options_;
  LightSampler lights_;
  float eps_;
};

// Light from a directional light (a delta in direction, never hit by scattering: no MIS):
// f * E cos_x * V(x, toward the light) / P(k), with s.beta = E / P(k). From the environment
// (s.beta = L(w) / (P(env) p(w)), s.pdf = P(env) p(w)): the same, weighted against cosine
// sampling, which finds the environment when a scattered ray leaves the scene.
glm::vec3 Tracer::directional(const Hit& x, const LightStart& s, std::uint64_t salt) const {
  const glm::vec3 w = -s.normal;
  const float cos_x = glm::dot(x.ns, w);
  if (cos_x <= 0.0f || glm::dot(x.ng, w) <= 0.0f) return glm::vec3(0.0f);
  if (rays_.occluded(x.position + eps_ * x.ng, w, 0.0f, std::numeric_limits<float>::infinity(),
                     salt))
    return glm::vec3(0.0f);
  const float weight = s.environment ? power_heuristic(s.pdf, x.scatter_pdf(w, cos_x)) : 1.0f;
  if (x.brdf) return s.beta * (cos_x * weight) * x.f(w);
  return s.beta * (cos_x * weight) * x.albedo * inv_pi;
}

// Radiance of the environment along a ray that left the scene: what a camera ray sees
// (core/scene/scene.h background_radiance), the map after a mirror (weight 1: no light sample
// reaches it through the mirror), else the map weighted against the light samples (MIS).
glm::vec3 Tracer::escaped(const glm::vec3& dir, int depth, bool specular, double bsdf_pdf) const {
  if (depth == 0) return background_radiance(scene_, dir);
  if (!scene_.has_environment()) return glm::vec3(0.0f);
  const glm::vec3 l = scene_.environment->radiance(dir);
  if (specular) return l;
  return l * power_heuristic(bsdf_pdf, lights_.environment_pdf(dir));
}

// Light from one sampled light to x: f * L * G / p, weighted against cosine sampling (MIS). An
// emitter point is weighted by its presence P (walk/rays/alpha.h): scattering finds it with
// probability P, so both strategies estimate P L_e.
glm::vec3 Tracer::next_event(const Hit& x, Pcg32& rng, std::uint64_t salt) const {
  LightStart s = lights_.sample(scene_, rng.next_double(), rng.next_double());
  s.beta *= light_presence(scene_, s);
  if (s.kind == VplKind::Directional) return directional(x, s, salt);
  // The shadow ray leaves from the offset point and aims at the sample itself, stopping short of
  // it: a segment toward a point of the emitter's plane meets that plane only at its end, also
  // at grazing angles (aimed from x but started eps above it, it crossed the plane beside the
  // sample and hit the emitter).
  const glm::vec3 from = x.position + eps_ * x.ng;
  const glm::vec3 d = s.position - from;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > eps_ * eps_)) return glm::vec3(0.0f);
  const float dist = std::sqrt(dist2);
  const glm::vec3 w = d / dist; // toward the light
  const float cos_x = glm::dot(x.ns, w);
  if (cos_x <= 0.0f || glm::dot(x.ng, w) <= 0.0f) return glm::vec3(0.0f);
  const float cos_y = -glm::dot(s.normal, w);
  float profile = 1.0f; // what the light sends toward x per unit of beta
  switch (s.kind) {
  case VplKind::Surface:
    profile = glm::max(cos_y, 0.0f);
    break;
  case VplKind::TwoSided:
    profile = std::abs(cos_y);
    break;
  case VplKind::Point:
  case VplKind::Directional: // handled above
    break;
  case VplKind::Spot:
    profile = spot_falloff(cos_y, s.cos_inner, s.cos_outer);
    break;
  }
  if (profile <= 0.0f) return glm::vec3(0.0f);
  if (rays_.occluded(from, w, 0.0f, dist - eps_, salt)) return glm::vec3(0.0f);
  float weight = 1.0f; // punctual lights cannot be hit by scattering
  if (s.triangle >= 0) {
    const double light_pdf = s.pdf * dist2 / profile; // solid angle at x
    weight = power_heuristic(light_pdf, x.scatter_pdf(w, cos_x));
  }
  if (x.brdf) return s.beta * (profile * cos_x / dist2 * weight) * x.f(w);
  return s.beta * (profile * cos_x / dist2 * weight) * x.albedo * inv_pi;
}

// The next direction from x: cosine-weighted on a Lambertian surface (f cos / pdf = rho), by the
// BRDF's sampler otherwise; nullopt when it falls below the surface (shading or geometric).
std::optional<Scatter> scatter(const Hit& x, Pcg32& rng) {
  const double u = rng.next_double(), v = rng.next_double();
  if (x.brdf) {
    const std::optional<BrdfSample> s = x.brdf->sample(x.wo, float(u), float(v));
    if (!s || glm::dot(s->wi, x.ng) <= 0.0f) return std::nullopt;
    return Scatter{s->wi, s->weight, s->pdf};
  }
  const glm::vec3 next = cosine_direction(x.ns, u, v);
  const float cos_n = glm::dot(next, x.ns);
  if (glm::dot(next, x.ng) <= 0.0f || cos_n <= 0.0f) return std::nullopt;
  return Scatter{next, x.albedo, cos_n * inv_pi};
}

// MIS weight of emission found by cosine sampling (solid-angle pdf bsdf_pdf at `from`).
float Tracer::emitter_weight(const Hit& y, const glm::vec3& from, double bsdf_pdf) const {
  const double area_pdf = lights_.area_pdf(scene_, y.triangle);
  if (area_pdf <= 0.0) return 1.0f;
  const glm::vec3 d = y.position - from;
  const float dist2 = glm::dot(d, d);
  const float cos_y = std::abs(glm::dot(y.ng, d)) / std::sqrt(dist2);
  if (cos_y <= 0.0f) return 0.0f;
  return power_heuristic(bsdf_pdf, area_pdf * dist2 / cos_y);
}

glm::vec3 Tracer::radiance(const glm::vec3& eye, const glm::vec3& dir0, float tmin, Pcg32& rng,
                           std::uint64_t salt) const {
  glm::vec3 sum(0.0f), throughput(1.0f), origin = eye, dir = dir0;
  double bsdf_pdf = 0.0; // solid-angle pdf of the direction that led here (0: camera ray)
  bool specular = false; // the direction that led here was a mirror reflection (a delta)
  for (int depth = 0; depth <= options_.max_depth; ++depth) {
    const auto h = rays_.intersect(origin, dir, depth == 0 ? tmin : 0.0f,
                                   std::numeric_limits<float>::infinity(), salt);
    if (!h) {
      sum += throughput * escaped(dir, depth, specular, bsdf_pdf);
      break;
    }
    const Hit x = make_hit(scene_, *h, origin, dir);
    const glm::vec3 le = emitted(scene_, x);
    // After a camera ray or a mirror no light sample could have found this emitter: weight 1.
    if (le != glm::vec3(0.0f))
      sum +=
          throughput * le * (depth == 0 || specular ? 1.0f : emitter_weight(x, origin, bsdf_pdf));
    const Material& material = scene_.material_of(x.triangle);
    if (material.specular) { // perfect mirror (core/scene/mirrors.h): no next event, f/pdf = R
      throughput *= material.base_color;
      if (max3(throughput) <= 0.0f) break;
      origin = x.position + eps_ * x.ng;
      dir = dir - 2.0f * glm::dot(x.ng, dir) * x.ng;
      specular = true;
      continue;
    }
    specular = false;
    if (!x.brdf && max3(x.albedo) <= 0.0f) break;
    sum += throughput * next_event(x, rng, salt);
    const std::optional<Scatter> next = scatter(x, rng);
    if (!next) break;
    throughput *= next->weight;
    bsdf_pdf = next->pdf;
    if (depth >= 3) { // Russian roulette
      const float q = glm::min(max3(throughput), 0.95f);
      if (rng.next_double() >= q) break;
      throughput /= q;
    }
    origin = x.position + eps_ * x.ng;
    dir = next->direction;
  }
  return sum;
}

} // namespace

Image path_trace(const Scene& scene, const RayScene& rays, const View& view,
                 const PathTracerOptions& options,
                 const std::function<void(int rows_done, int rows)>& progress) {
  const Tracer tracer(scene, rays, options);
  Image image(view.width, view.height);
  const std::uint64_t seed = mix64(options.seed);
  const std::uint32_t end = options.end_sample == 0 ? options.spp : options.end_sample;
  if (options.first_sample >= end || end > options.spp)
    throw Error("", "--spp-range",
                fmt::format("{}:{} is not a non-empty range within 0:{}", options.first_sample, end,
                            options.spp));
  const auto alpha = static_cast<float>(double(end - options.first_sample) / options.spp);
  auto row = [&](int y) {
    for (int x = 0; x < view.width; ++x) {
      if (options.cancel != nullptr && options.cancel->load(std::memory_order_relaxed)) return;
      const CameraRay ray = pixel_ray(view, x, y);
      const std::uint64_t pixel = static_cast<std::uint64_t>(y) * view.width + x;
      glm::dvec3 sum(0.0);
      for (std::uint32_t s = options.first_sample; s < end; ++s) {
        Pcg32 rng(mix64(seed ^ pixel), s); // one stream per pixel and sample
        CameraRay r = ray;
        if (options.pixel_footprint) {
          const auto u = static_cast<float>(rng.next_double());
          const auto v = static_cast<float>(rng.next_double());
          r = image_point_ray(view, static_cast<float>(x) + u, static_cast<float>(y) + v);
        }
        const glm::vec3 l =
            tracer.radiance(r.origin, r.direction, view.znear, rng, mix64(seed ^ pixel) + s);
        if (std::isfinite(l.x) && std::isfinite(l.y) && std::isfinite(l.z)) sum += glm::dvec3(l);
      }
      image.at(x, y) = glm::vec4(glm::vec3(sum / static_cast<double>(options.spp)), alpha);
    }
  };
  parallel_rows(view.height, options.threads, row, [&](int done) {
    if (progress) progress(done, view.height);
  });
  return image;
}

} // namespace irad
