#pragma once
// Which optional material features a scene uses; the raster's programs compile only those
// (raster/scene/material_glsl.h), so a scene without them pays nothing.
#include "core/scene/scene.h"

#include <glad/gl.h>

namespace irad::gl {

struct MaterialFeatures {
  bool uv1 = false;    // Scene::uvs1 is not empty
  bool colors = false; // Scene::colors is not empty
  bool alpha = false;  // some material is Mask or Blend
  // Some material is a mirror (core/scene/mirrors.h): the batched shadow atlas draws mirrored VPLs'
  // cubes (raster/glsl/batched_shaders.h, IRAD_MIRRORS).
  bool mirrors = false;
  // Some material is not Lambertian (Scene::all_lambertian false): the camera passes read the
  // glTF BRDF's inputs and the shading evaluates it (IRAD_GLOSSY).
  bool glossy = false;
  // Scene::tangents is not empty (some material has a normal map): the tangent attribute and the
  // normal map's lookup (IRAD_NORMAL_MAP).
  bool normal_maps = false;
  static MaterialFeatures of(const Scene& scene);
};

// Vertex attribute locations of GpuScene's optional buffers (0-2: position, normal, uv).
inline constexpr GLuint kUv1Attribute = 3;
inline constexpr GLuint kColorAttribute = 4;
inline constexpr GLuint kTangentAttribute = 5;

} // namespace irad::gl
