#pragma once
// Exact-visibility evaluation of a VPL list at one surface point: the rt-vpl estimator's core,
// also used by the clamp's bias compensation.
#include "core/camera/view.h"
#include "core/lights/vpl.h"
#include "core/scene/scene.h"
#include "walk/rays/ray_scene.h"

#include <algorithm>
#include <cstddef>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <vector>

namespace irad {

// A glossy point's BRDF and the direction it is seen from.
struct GlossyView {
  Brdf brdf;
  glm::vec3 wo;
  // The specular lobe is the glossy camera pass's (walk/estimators/glossy_pass.h): the VPLs whose
  // light a ray can meet (Vpl::ray_reachable) are weighed by the diffuse lobe alone.
  bool traced_specular = false;
};

// A surface point seen along a ray, with its normals turned toward the ray's origin.
struct ShadingPoint {
  glm::vec3 position;
  glm::vec3 normal;    // shading normal on the side the ray came from (as gl_FrontFacing)
  glm::vec3 geometric; // geometric normal on that side
  glm::vec3 albedo;
  glm::vec3 emission; // L_e toward the ray's origin (front face only unless double-sided)
  // Where the material is not Lambertian: its BRDF (about `normal`) and the unit direction
  // toward the ray's origin; null otherwise (a Lambertian point stays this small).
  std::shared_ptr<const GlossyView> glossy;
};

ShadingPoint shading_point(const Scene& scene, const RayHit& hit, const glm::vec3& origin,
                           const glm::vec3& dir);

// The diffuse point the centre of pixel (x, y) sees, if any (nothing: the background or a mirror).
std::optional<ShadingPoint> visible_point(const Scene& scene, const RayScene& rays,
                                          const View& view, int x, int y);

// The VPLs' reflected radiance at x toward the viewer:
//   rho(x)/pi * sum_k I_k E_k cos_x / max(d^2, d_min^2) V(y_k, x)   (core/lights/vpl.h),
// with f_r,x(toward y_k, x.wo) in place of rho(x)/pi inside the sum where x has a BRDF,
// with V from shadow rays (for a mirrored VPL, V through its mirror polygon:
// walk/rays/mirror_walk.h). x must not lie on a mirror (a mirror reflects nothing diffusely:
// walk/estimators/mirror_pass.h). d_min: the VPL's own clamp_distance, else dmin (the global clamp,
// world units; core/lights/vpl.h clamp_distance2); eps: the scene's ray offset.
glm::vec3 gather_vpls(const RayScene& rays, const ShadingPoint& x, const VplSet& vpls, float dmin,
                      float eps);

// What weighs VPL v's term (vpl_irradiance) at x: f_r,x(x.wo, toward v) where x has a BRDF (its
// diffuse lobe alone where the glossy pass traces the specular one and v is ray_reachable), else
// rho(x)/pi.
glm::vec3 receiver_brdf(const ShadingPoint& x, const Vpl& v);

// Whether the glossy camera pass traces x's specular lobe: x has a BRDF of roughness below
// `roughness` (0: never).
bool narrow_lobe(const ShadingPoint& x, float roughness);
// x with GlossyView::traced_specular set where narrow_lobe.
void mark_traced_specular(ShadingPoint& x, float roughness);

// One VPL's term of that sum without rho(x)/pi: I_k E_k cos_x / max(d^2, d_min^2) V(y_k, x)
// (for a directional VPL, gather_directional's), E_k times the lobe's shape for a glossy VPL
// (core/lights/vpl.h vpl_lobe_shape); the set's mirror polygons and lobes.
glm::vec3 vpl_irradiance(const RayScene& rays, const ShadingPoint& x, const Vpl& v,
                         const VplSet& set, float dmin, float eps);

// vpl_irradiance of vpls.vpls[first, first + n) at x into out[0, n), n <= kVplChunk: the same
// terms, the plain VPLs' shadow rays traced together (RayScene's packets; mirrored and
// directional VPLs test their own visibility).
inline constexpr std::size_t kVplChunk = 64;
void vpl_irradiance_chunk(const RayScene& rays, const ShadingPoint& x, const VplSet& vpls,
                          std::size_t first, std::size_t n, float dmin, float eps, glm::vec3* out);
// The same for any n <= kVplChunk VPLs of `set` (its lobes and mirror polygons), by pointer.
void vpl_terms(const RayScene& rays, const ShadingPoint& x, const Vpl* const* vpls, std::size_t n,
               const VplSet& set, float dmin, float eps, glm::vec3* out);

// f(j, vpl_irradiance of VPL j at x) for every VPL of the set in order, kVplChunk at a time
// (vpl_irradiance_chunk): gather_vpls and the light rows go through it.
template <class F>
void for_each_vpl_irradiance(const RayScene& rays, const ShadingPoint& x, const VplSet& vpls,
                             float dmin, float eps, F&& f) {
  glm::vec3 terms[kVplChunk];
  for (std::size_t first = 0; first < vpls.vpls.size(); first += kVplChunk) {
    const std::size_t n = std::min(kVplChunk, vpls.vpls.size() - first);
    vpl_irradiance_chunk(rays, x, vpls, first, n, dmin, eps, terms);
    for (std::size_t j = 0; j < n; ++j) f(first + j, terms[j]);
  }
}

// E_k of core/lights/vpl.h: the VPL's emission profile toward a direction with cosine cos_y (1 for
// a directional VPL, which gather_directional() evaluates).
float emission_profile(const Vpl& v, float cos_y);
// A directional VPL's I max(0, n_x . -d) V(x, -d), V from a shadow ray to infinity (without
// rho(x)/pi).
glm::vec3 gather_directional(const RayScene& rays, const ShadingPoint& x, const Vpl& v, float eps);

} // namespace irad
