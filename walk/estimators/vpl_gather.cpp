#include "walk/estimators/vpl_gather.h"

#include "core/material/surface_material.h"
#include "walk/rays/mirror_walk.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace irad {

std::optional<ShadingPoint> visible_point(const Scene& scene, const RayScene& rays,
                                          const View& view, int x, int y) {
  const CameraRay ray = pixel_ray(view, x, y);
  const auto hit = rays.intersect(ray.origin, ray.direction, view.znear, 2.0f * view.zfar);
  if (!hit || scene.material_of(hit->triangle).specular) return std::nullopt;
  return shading_point(scene, *hit, ray.origin, ray.direction);
}

ShadingPoint shading_point(const Scene& scene, const RayHit& hit, const glm::vec3& origin,
                           const glm::vec3& dir) {
  const SurfacePoint sp = surface_at(scene, hit.triangle, hit.bary);
  const bool front = glm::dot(sp.geometric_normal, dir) < 0.0f;
  const Material& m = scene.material_of(hit.triangle);
  ShadingPoint x;
  x.position = origin + hit.t * dir;
  x.normal = front ? sp.shading_normal : -sp.shading_normal;
  x.geometric = front ? sp.geometric_normal : -sp.geometric_normal;
  x.albedo = albedo_at(scene, hit.triangle, hit.bary);
  x.emission =
      (front || m.double_sided) ? emission_at(scene, hit.triangle, hit.bary) : glm::vec3(0.0f);
  if (!m.lambertian() && !m.specular) {
    const glm::vec3 n = glm::dot(x.normal, x.geometric) > 0.0f ? x.normal : x.geometric;
    x.glossy = std::make_shared<const GlossyView>(GlossyView{
        Brdf(brdf_inputs_at(scene, hit.triangle, hit.bary), facing_normal(n, -dir)), -dir});
  }
  return x;
}

float emission_profile(const Vpl& v, float cos_y) {
  switch (v.kind) {
  case VplKind::Surface:
    return glm::max(cos_y, 0.0f);
  case VplKind::TwoSided:
    return std::abs(cos_y);
  case VplKind::Point:
    return 1.0f;
  case VplKind::Spot:
    return spot_falloff(cos_y, v.cos_inner, v.cos_outer);
  case VplKind::Directional:
    return 1.0f;
  }
  return 0.0f;
}

// A light at infinity along v.normal: E cos_x V with the shadow ray going to infinity.
glm::vec3 gather_directional(const RayScene& rays, const ShadingPoint& x, const Vpl& v, float eps) {
  const float cos_x = -glm::dot(x.normal, v.normal);
  if (cos_x <= 0.0f) return glm::vec3(0.0f);
  if (rays.occluded(x.position, -v.normal, eps, std::numeric_limits<float>::infinity()))
    return glm::vec3(0.0f);
  return v.intensity * cos_x;
}

namespace {

// A point or surface VPL's term without V, and the shadow ray that decides V: from x toward the
// VPL, t in (eps, tmax). Zero (and no ray needed) where the VPL does not reach x.
struct Unshadowed {
  glm::vec3 term{0.0f};
  glm::vec3 toward{0.0f}; // unit, x -> VPL
  float tmax = 0.0f;
};

Unshadowed unshadowed(const ShadingPoint& x, const Vpl& v, const VplSet& set, float dmin,
                      float eps) {
  const glm::vec3 d = x.position - v.position;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > eps * eps)) return {};
  const float dist = std::sqrt(dist2);
  const glm::vec3 w = d / dist;
  const float cos_x = -glm::dot(x.normal, w);
  if (cos_x <= 0.0f) return {};
  const float e = emission_profile(v, glm::dot(v.normal, w));
  if (e <= 0.0f) return {};
  const float dmin2 = clamp_distance2(v, dmin);
  const float g = e * cos_x / glm::max(dist2, dmin2);
  if (v.lobe >= 0) { // a virtual spherical light of the clamp's radius (vpl_lobe_shape)
    const glm::vec3 shape =
        vpl_lobe_shape(set.lobes[std::size_t(v.lobe)], v, w, std::sqrt(dmin2) / dist);
    return {v.intensity * shape * g, -w, dist - eps};
  }
  return {v.intensity * g, -w, dist - eps};
}

} // namespace

glm::vec3 vpl_irradiance(const RayScene& rays, const ShadingPoint& x, const Vpl& v,
                         const VplSet& set, float dmin, float eps) {
  if (v.kind == VplKind::Directional) return gather_directional(rays, x, v, eps);
  const Unshadowed u = unshadowed(x, v, set, dmin, eps);
  if (u.term == glm::vec3(0.0f)) return u.term;
  // Shadow ray from the receiver toward the VPL, stopping short of both ends; a mirrored VPL
  // (core/scene/mirrors.h) by way of its mirror polygon.
  if (v.mirror >= 0 ? !mirrored_visible(rays, v, set.mirrors[static_cast<std::size_t>(v.mirror)],
                                        x.position, eps)
                    : rays.occluded(x.position, u.toward, eps, u.tmax))
    return glm::vec3(0.0f);
  return u.term;
}

void vpl_irradiance_chunk(const RayScene& rays, const ShadingPoint& x, const VplSet& vpls,
                          std::size_t first, std::size_t n, float dmin, float eps, glm::vec3* out) {
  const Vpl* chunk[kVplChunk];
  for (std::size_t i = 0; i < n; ++i) chunk[i] = &vpls.vpls[first + i];
  vpl_terms(rays, x, chunk, n, vpls, dmin, eps, out);
}

void vpl_terms(const RayScene& rays, const ShadingPoint& x, const Vpl* const* vpls, std::size_t n,
               const VplSet& set, float dmin, float eps, glm::vec3* out) {
  glm::vec3 toward[kVplChunk] = {};
  float tmax[kVplChunk] = {};
  bool blocked[kVplChunk];
  std::size_t index[kVplChunk];
  std::size_t rays_n = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vpl& v = *vpls[i];
    if (v.kind == VplKind::Directional || v.mirror >= 0) { // their own visibility tests
      out[i] = vpl_irradiance(rays, x, v, set, dmin, eps);
      continue;
    }
    const Unshadowed u = unshadowed(x, v, set, dmin, eps);
    out[i] = u.term;
    if (u.term == glm::vec3(0.0f)) continue;
    toward[rays_n] = u.toward;
    tmax[rays_n] = u.tmax;
    index[rays_n++] = i;
  }
  rays.occluded(x.position, toward, tmax, rays_n, eps, blocked);
  for (std::size_t k = 0; k < rays_n; ++k)
    if (blocked[k]) out[index[k]] = glm::vec3(0.0f);
}

glm::vec3 receiver_brdf(const ShadingPoint& x, const Vpl& v) {
  if (!x.glossy) return x.albedo * std::numbers::inv_pi_v<float>;
  const glm::vec3 toward =
      v.kind == VplKind::Directional ? -v.normal : glm::normalize(v.position - x.position);
  if (x.glossy->traced_specular && v.ray_reachable())
    return x.glossy->brdf.eval_diffuse(x.glossy->wo, toward);
  return x.glossy->brdf.eval(x.glossy->wo, toward);
}

bool narrow_lobe(const ShadingPoint& x, float roughness) {
  return x.glossy && x.glossy->brdf.inputs().roughness < roughness;
}

void mark_traced_specular(ShadingPoint& x, float roughness) {
  if (!narrow_lobe(x, roughness) || x.glossy->traced_specular) return;
  GlossyView marked = *x.glossy;
  marked.traced_specular = true;
  x.glossy = std::make_shared<const GlossyView>(marked);
}

glm::vec3 gather_vpls(const RayScene& rays, const ShadingPoint& x, const VplSet& vpls, float dmin,
                      float eps) {
  glm::vec3 sum(0.0f);
  if (x.glossy) { // f_r,x per VPL, from the direction its light arrives from
    for_each_vpl_irradiance(rays, x, vpls, dmin, eps, [&](std::size_t j, const glm::vec3& term) {
      if (term != glm::vec3(0.0f)) sum += term * receiver_brdf(x, vpls.vpls[j]);
    });
    return sum;
  }
  for_each_vpl_irradiance(rays, x, vpls, dmin, eps,
                          [&sum](std::size_t, const glm::vec3& term) { sum += term; });
  return sum * x.albedo * std::numbers::inv_pi_v<float>;
}

} // namespace irad
