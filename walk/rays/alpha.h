#pragma once
// glTF alphaMode for the CPU rays (core/scene/scene.h, AlphaMode): where a surface is there.
//   coverage a(x) = base_alpha * alpha of base_color_texture at the material's uv map
//                   * COLOR_0 alpha (when the scene has vertex colours),
//   presence P(x) = 1 (Opaque), [a >= alpha_cutoff] (Mask), clamp(a, 0, 1) (Blend):
// the probability that a ray or particle stops at x. RayScene (walk/rays/ray_scene.h) applies it in
// Embree filter functions; light sampling weights emitter points by it.
// The coverage a(x) is core's coverage_at (core/scene/scene.h), the one rule the raster shares.
#include "core/lights/light_sampler.h"
#include "core/scene/scene.h"

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>

namespace irad {

// Whether some material is Mask or Blend (only then are filter functions installed).
bool has_alpha(const Scene& scene);

// P(x) above, in [0, 1]; 1 for an opaque material without looking at its coverage.
float presence_at(const Scene& scene, std::size_t triangle, glm::vec2 bary);

// P at a light start (core/lights/light_sampler.h): the emitter's presence at the sampled point, 1
// for a punctual light. Light sampling keeps the emitter's full triangle (its power and pdf) and
// multiplies beta_0 by P: a point of a Mask cut-out carries nothing, a Blend emitter a times its
// emission (the expected emission of a surface that is there with probability a); both unbiased.
float light_presence(const Scene& scene, const LightStart& start);

// Whether a ray stops at a surface of presence p, given a uniform number u in [0, 1): u < p.
// Mask (p in {0, 1}) needs no random number: every u gives the same answer.
inline bool stops(float presence, double u) {
  return u < static_cast<double>(presence);
}

} // namespace irad
