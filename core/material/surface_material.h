#pragma once
// The glTF material of a scene point as the BRDF sees it (design.md section 1b): factors times
// textures, and the normal map.
#include "core/material/brdf.h"
#include "core/scene/scene.h"

#include <cstddef>
#include <vector>

namespace irad {

// base = albedo_at (base colour x texture x COLOR_0), m = metallic x texture B, r = roughness x
// texture G, f0 = min(((ior - 1)/(ior + 1))^2 specular_color x texture rgb, 1) s and f90 = s with
// s = specular_factor x specular texture alpha. A Lambertian material (Material::lambertian) gives
// m = f0 = f90 = 0 without reading any texture but the base colour's.
BrdfInputs brdf_inputs_at(const Scene& scene, std::size_t t, glm::vec2 bary);

// The same with every texture at its texel mean and COLOR_0 at the triangle's centroid: what the
// walk's mean albedo takes for a triangle. `texture_means` holds Texture::mean() of every texture
// of the scene (texture_means(scene), computed once).
BrdfInputs mean_brdf_inputs(const Scene& scene, std::size_t t,
                            const std::vector<glm::vec4>& texture_means);
std::vector<glm::vec4> texture_means(const Scene& scene);

// The unit shading normal of triangle t at bary after its material's normal map:
// normalize(x T + y B + z N) with (x, y, z) = (2 texel - 1) and x, y scaled by normal_scale, T the
// interpolated tangent made orthogonal to the interpolated normal N, B = w cross(N, T).
// `normal` (the interpolated one) when the material has no normal map or the scene no tangents
// or texture coordinates for it.
glm::vec3 mapped_normal(const Scene& scene, std::size_t t, glm::vec2 bary, const glm::vec3& normal);

} // namespace irad
