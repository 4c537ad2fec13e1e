#pragma once
// Tabulated integrals that make the directional albedo of the glTF BRDF (core/material/brdf.h)
// a few lookups. With mu = n.v, r the perceptual roughness (alpha = r^2), w(v.h) = (1 - |v.h|)^5
// the Schlick weight and h = normalize(v + l), over the hemisphere of l:
//   S(mu, r) = integral of V D (n.l) dl          (the specular lobe with F = 1)
//   W(mu, r) = integral of w(v.h) V D (n.l) dl
//   Q(mu)    = integral of w(v.h) (n.l)/pi dl     (the Schlick weight the diffuse lobe loses)
// so that with Schlick's F = f0 + (f90 - f0) w, integral F V D (n.l) = f0 (S - W) + f90 W and
// integral (1 - F) (n.l)/pi = 1 - f0 (1 - Q) - f90 Q. The hemispherical means (2 integral of
// x(mu) mu dmu) give the cosine-weighted average over incident directions.
// Computed once per process, on first use (about 60 ms on this machine): a scene whose
// materials are all Lambertian never builds it.
#include <array>

namespace irad {

class AlbedoTable {
public:
  static constexpr int kMu = 32;    // mu nodes i / (kMu - 1) (mu = 0 evaluated at 1e-3)
  static constexpr int kRough = 32; // r nodes j / (kRough - 1)

  struct Terms {
    float s = 0.0f, w = 0.0f, q = 0.0f;
  };
  // Bilinear in (mu, r), both clamped to [0, 1].
  Terms at(float mu, float roughness) const;
  // Cosine-weighted means over mu, linear in r.
  Terms hemispherical(float roughness) const;

  // Node (mu_i, r_j) at cells()[i * kRough + j] (what the raster uploads as a texture).
  const std::array<Terms, kMu * kRough>& cells() const { return cells_; }

  // The process's table (built on the first call; thread-safe).
  static const AlbedoTable& get();

private:
  AlbedoTable();
  std::array<Terms, kMu * kRough> cells_{};
  std::array<Terms, kRough> means_{};
};

// The smallest alpha the BRDF uses: r^2 below it is raised to it (a GGX lobe of alpha 0 is a delta
// that no estimator here can sample; perfect mirrors are Material::specular).
inline constexpr float kMinAlpha = 1e-3f;
inline float alpha_of(float roughness) {
  const float a = roughness * roughness;
  return a > kMinAlpha ? a : kMinAlpha;
}

} // namespace irad
