#pragma once
// Virtual point lights: what the walk hands to the estimators (design.md section 1).
// A VPL at y lights a receiver x (normal n_x, albedo rho(x)) with
//   C(x) = intensity * E(y, x) * max(0, cos theta_x) / max(|x - y|^2, d_min^2) * V(y, x) *
//   rho(x)/pi
// where the emission profile E depends on the kind:
//   Surface:   max(0, cos theta_y)  (theta_y between normal and x - y)
//   TwoSided:  |cos theta_y|        (a point on a double-sided emitter)
//   Point:     1                    (a punctual light; no clamp, it is exact and not a sample)
//   Spot:      glTF smooth cone falloff around `normal` (the spot axis); no clamp either.
// A Directional VPL is a light at infinity travelling along `normal` (d): it has no position (the
// field holds where its particle started) and
//   C(x) = intensity * max(0, n_x . (-d)) * V(x, -d to infinity) * rho(x)/pi   (no 1/r^2, no
//   clamp).
// `intensity` already folds in the weight w = 1/n_j, the path throughput beta_j and, for depth >=
// 1, rho(y_j)/pi, so an estimator adds C(x) of every VPL and nothing else.
// A glossy VPL (lobe >= 0: its point's material is not Lambertian, design.md 1b) sends
// w beta_j f_r,y(incident, w_out) instead of w beta_j rho/pi: its intensity is that of the
// Lambertian VPL of the same reflected power, w beta_j a(incident)/pi with a the directional
// albedo (what the raster draws), and the CPU estimators multiply its E by the lobe's shape
// pi f_r,y(incident, w_out) / a(incident) (vpl_lobe_shape), per channel. A receiver x weighs the
// arriving light by f_r,x(toward y, toward the eye) where the text above says rho(x)/pi.
// A mirrored VPL (mirror >= 0, core/scene/mirrors.h) is the image of a VPL in a planar mirror: it
// lights only the x on the positive side of mirror_plane whose segment from it crosses the plane
// inside the polygon VplSet::mirrors[mirror], with V = free segments y -> m and m -> x.
#include "core/material/brdf.h"
#include "core/scene/mirror_polygon.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace irad {

class ClampField; // core/lights/clamp_field.h

enum class VplKind : std::uint8_t { Surface, TwoSided, Point, Spot, Directional };

struct Vpl {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f}; // unit; the spot axis for Spot, d for Directional
  glm::vec3 intensity{0.0f};
  VplKind kind = VplKind::Surface;
  bool environment = false; // Directional only: one of the environment's directions (not a sun)
  std::uint16_t depth = 0;  // reflections before this VPL (0: on a light)
  std::uint32_t path = 0;   // particle index i
  float cos_inner = 1.0f;   // Spot only: cosines of the inner and outer cone angles
  float cos_outer = 0.0f;
  std::int32_t mirror = -1;     // mirrored VPL: index in VplSet::mirrors; -1: ordinary
  glm::vec4 mirror_plane{0.0f}; // mirrored VPL: (n, w), n toward the side it lights
  // d_min of this VPL in world units (core/lights/clamp_field.h, the local clamp); 0: the
  // estimator's global clamp (a fraction of the bounding diagonal). Unused for unclamped kinds.
  float clamp_distance = 0.0f;
  // Glossy VPL: index into VplSet::lobes; -1: Lambertian.
  std::int32_t lobe = -1;

  bool clamped() const { return kind == VplKind::Surface || kind == VplKind::TwoSided; }
  // Whether the glossy camera pass (walk/estimators/glossy_pass.h) gathers this VPL's light by
  // rays: a surface VPL the walk left after a reflection (the rays meet the surface that reflects
  // it), or an environment direction (the rays that leave the scene read the map). The lights' own
  // VPLs (emitters, points, spots, suns) stay the VPL estimators', with the full BRDF: they are
  // the light sampling of the direct light, where rays alone would find small bright emitters
  // by chance (fireflies).
  bool ray_reachable() const {
    return (clamped() && depth > 0) || (kind == VplKind::Directional && environment);
  }
  // Whether any channel of the intensity is positive (a black VPL draws no pass).
  bool carries_light() const {
    return intensity.x > 0.0f || intensity.y > 0.0f || intensity.z > 0.0f;
  }
};

// The squared clamp distance d_min^2 of v in the estimator's geometry term: 0 for the unclamped
// kinds, else its own clamp_distance or, without one, global_dmin (world units).
inline float clamp_distance2(const Vpl& v, float global_dmin) {
  if (!v.clamped()) return 0.0f;
  const float d = v.clamp_distance > 0.0f ? v.clamp_distance : global_dmin;
  return d * d;
}

// glTF KHR_lights_punctual spot falloff: smoothstep-free quadratic ramp between the cones.
inline float spot_falloff(float cos_angle, float cos_inner, float cos_outer) {
  const float scale = 1.0f / glm::max(1e-3f, cos_inner - cos_outer);
  const float t = glm::clamp((cos_angle - cos_outer) * scale, 0.0f, 1.0f);
  return t * t;
}

// The material at a glossy VPL's point, the unit direction its particle arrived from (away from
// the point) and the directional albedo a(incident).
struct VplLobe {
  BrdfInputs material;
  glm::vec3 incident{0.0f};
  glm::vec3 albedo{0.0f};
};

// pi f_r,y(incident, w) / a(incident) per channel (0 where a is 0), the glossy VPL v's emission
// toward unit w relative to a Lambertian VPL's, about v.normal; a mirrored copy (v.mirror >= 0)
// reflects the lobe's incident direction in its mirror plane, as it reflects its normal.
// spread = r / d > 0: the lobe of a virtual spherical light of radius r seen from d away (Hasan,
// Krivanek, Walter & Bala 2009: a VPL's light spread over its neighbourhood, so that a narrow lobe
// lands as a patch, not a spike), approximated by the lobe widened to spread_roughness and
// divided by the widened lobe's albedo (the VPL's power stays). The estimators take r = the VPL's
// clamp distance (its neighbours' spacing under the local clamp); spread 0: the point's lobe.
glm::vec3 vpl_lobe_shape(const VplLobe& lobe, const Vpl& v, const glm::vec3& w,
                         float spread = 0.0f);
// The lobe's incident direction as v sends it: reflected in v's mirror plane for a mirrored copy.
glm::vec3 lobe_incident(const VplLobe& lobe, const Vpl& v);
// v's lobe in `lobes` (VplSet::lobes), or nullptr for a Lambertian VPL or an index outside them.
inline const VplLobe* find_lobe(const std::vector<VplLobe>& lobes, const Vpl& v) {
  return v.lobe >= 0 && static_cast<std::size_t>(v.lobe) < lobes.size()
             ? &lobes[static_cast<std::size_t>(v.lobe)]
             : nullptr;
}
// The perceptual roughness of a lobe of `roughness` seen through a sphere of angular radius
// about `spread` (radians): alpha'^2 = alpha^2 + (spread / 2)^2 (the reflected direction moves by
// twice the half vector's angle), alpha' at most 1.
float spread_roughness(float roughness, float spread);

struct VplSet {
  std::vector<Vpl> vpls;
  std::uint32_t paths = 0; // N
  double rho_bar = 0.0;
  int l_max = 0;
  bool depth_capped = false; // rho_bar near or above 1 hit the depth cap
  std::uint64_t planned = 0; // M = sum n_j: VPLs before misses and absorption
  // The mirror polygons of the scene (core/scene/mirrors.h), which mirrored VPLs index; empty
  // without mirrors. Mirrored copies are not counted in `planned`.
  std::vector<MirrorPolygon> mirrors;
  // The local clamp (core/lights/clamp_field.h) the VPLs' clamp_distance came from, for the
  // estimators that need d(y) away from the VPLs (the clamp's residual); null with the global
  // clamp.
  std::shared_ptr<const ClampField> clamp_field;
  // The glossy VPLs' lobes (Vpl::lobe); empty when every surface is Lambertian.
  std::vector<VplLobe> lobes;
};

} // namespace irad
