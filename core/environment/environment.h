#pragma once
// A distant environment: radiance L(w) arriving from every direction w (unit, pointing from the
// scene toward the sky), stored as an equirectangular map (width = 2 height), piecewise constant
// per texel (nearest lookup everywhere: walk, pt, rt-vpl and the raster's background agree
// exactly).
//
// Orientation (Blender's equirectangular world texture, so a Cycles render of the same map
// matches, with glTF's +Y up; Blender's (x, y, z) = glTF's (x, -z, y)): for a map direction
// d = (x, y, z),
//   column u = 0.5 + atan2(z, x) / (2 pi)  in [0, 1] (1 only along -X: the last column), left to
//                                         right; the centre looks along +X,
//   row    v = acos(y) / pi               in [0, 1], top to bottom; the top row is the zenith +Y.
// Rotation: the map is turned by `rotation` radians about +Y (right-handed: +Z toward +X), so
// world direction w sees the map at d = R_y(-rotation) w; a feature of the map at d appears at
// R_y(rotation) d, i.e. a rotation by 360/W degrees shifts the image one column to the left.
//
// Importance sampling (design: a 2-D distribution over the map): texel (i, j) is chosen with
// probability P_ij = lum(L_ij) Omega_ij / S, S = sum lum(L) Omega, Omega_ij its solid angle
// (2 pi / W) (cos theta_top - cos theta_bottom), lum the Rec. 709 luminance; within the texel
// the direction is uniform in solid angle (phi uniform, cos theta uniform). So the density is
// constant per texel, pdf(w) = lum(L(w)) / S, and L(w) / pdf(w) has luminance S for every sample.
// A texel whose radiance is positive in some channel has lum > 0 (all coefficients are > 0),
// so every direction that carries light can be sampled: the estimators stay unbiased.
#include "core/image/image.h"

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace irad {

struct EnvironmentSample {
  glm::vec3 direction{0.0f, 1.0f, 0.0f}; // world, toward the sky
  glm::vec3 radiance{0.0f};              // L(direction), strength applied
  double pdf = 0.0;                      // solid-angle density of direction
};

class Environment {
public:
  // map: linear RGB radiance, width == 2 height >= 1 (alpha ignored), every texel finite and
  // >= 0 (the loader checks; here a violation throws irad::Error naming `source`). strength scales
  // the radiance; rotation in radians about +Y.
  Environment(Image map, float strength, float rotation, std::string source);
  // A uniform environment of radiance `radiance`: uniform_map(radiance), strength 1, no rotation.
  static Environment uniform(const glm::vec3& radiance, std::string source);
  // The 2 x 1 map of a uniform environment.
  static Image uniform_map(const glm::vec3& radiance);

  // Where the map's direction d lies in the world: R_y(rotation) d (what turns with the map, as
  // the sky's sun does).
  glm::vec3 to_world(const glm::vec3& d) const;
  // L(w) for a unit world direction (nearest texel, strength applied).
  glm::vec3 radiance(const glm::vec3& w) const;
  // A direction from (u, v) in [0, 1)^2 with the density above: u picks the row and then (rescaled)
  // cos theta within it, v the column and then phi. Never fails when total_luminance() > 0.
  EnvironmentSample sample(double u, double v) const;
  // The solid-angle density sample() gives unit world direction w.
  double pdf(const glm::vec3& w) const;

  // S = integral of lum(L(w)) over the sphere (strength applied).
  double total_luminance() const { return total_luminance_; }
  // integral of mean_rgb(L(w)) over the sphere: the power through a disk of area A facing the
  // scene from all directions is A times this.
  double mean_radiance_integral() const { return mean_integral_; }
  bool black() const { return !(total_luminance_ > 0.0); }
  // Whether camera rays that see no surface show L (--env-visible); the lighting is the same.
  bool visible = true;

  // The map as stored (strength not applied), its strength and rotation: what the raster uploads.
  const Image& map() const { return map_; }
  float strength() const { return strength_; }
  float rotation() const { return rotation_; }
  const std::string& source() const { return source_; }

  // Map texel of a map-frame direction d and the map-frame direction at (u, v) (column, row
  // fractions as above): the one convention, shared with the raster's GLSL (same formulas).
  static glm::vec2 map_coordinates(const glm::vec3& d);
  static glm::vec3 map_direction(double u, double v);

private:
  glm::vec3 to_map(const glm::vec3& w) const; // R_y(-rotation) w
  std::size_t texel_of(const glm::vec3& d) const;

  Image map_;
  float strength_ = 1.0f;
  float rotation_ = 0.0f;
  float cos_rotation_ = 1.0f, sin_rotation_ = 0.0f; // of rotation_, once (every lookup turns)
  std::string source_;
  std::vector<float> luminance_;   // lum(L_ij) per texel (strength applied)
  std::vector<double> row_cdf_;    // inclusive prefix sums of row weights / total, size height
  std::vector<double> column_cdf_; // per row, inclusive prefix sums / row total, width per row
  double total_luminance_ = 0.0;
  double mean_integral_ = 0.0;
};

// Rec. 709 luminance of linear RGB.
inline float luminance(const glm::vec3& c) {
  return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

} // namespace irad
