#pragma once
// Orthographic shadow map of a directional light: an R32F square over the scene's bounding sphere
// seen along the light's travel d, storing the depth dot(p - c, d) of the nearest surface (c: the
// centre of the bounds). Every directional VPL of one light has the same map, so the map is
// rendered again only when d changes (or after forget()).
#include "core/lights/vpl.h"
#include "core/scene/bounds.h"
#include "raster/context/shader_program.h"
#include "raster/scene/gpu_scene.h"
#include "raster/scene/material_glsl.h"

#include <glm/glm.hpp>

namespace irad::gl {

class OrthoShadow {
public:
  // features: the scene's (raster/scene/material_features.h); with alpha, absent fragments cast no
  // shadow.
  OrthoShadow(const GladGLContext& api, int resolution, const Bounds& bounds,
              const MaterialFeatures& features);

  // Makes the map hold direction `d` (unit): renders it unless it already does, which changes the
  // bound framebuffer, viewport and program. Returns whether it rendered.
  bool render(const glm::vec3& d, const GpuScene& scene);
  // The next render() draws anew (the geometry changed).
  void forget() { valid_ = false; }

  // World -> (u, v, depth along d), u and v in [0, 1] over the map.
  const glm::mat4& lookup() const { return lookup_; }
  GLuint texture() const { return map_.get(); }
  int resolution() const { return resolution_; }
  // Width of one texel in world units.
  float texel() const { return 2.0f * half_width_ / static_cast<float>(resolution_); }

private:
  const GladGLContext* api_;
  int resolution_;
  glm::vec3 centre_;
  float half_width_; // of the square the map covers: the bounding sphere's radius plus 1 %
  ShaderProgram program_;
  MaterialUniforms material_;
  GLint u_light_clip_, u_centre_, u_direction_;
  Texture map_;
  Renderbuffer depth_;
  Framebuffer fbo_;
  glm::vec3 direction_{0.0f};
  bool valid_ = false;
  glm::mat4 lookup_{1.0f};
};

// Half the width of the square a map covers: the bounding sphere's radius plus 1 %.
float ortho_half_width(const Bounds& bounds);
// Rows (t, b, d) of the light's frame (t, b from orthonormal_basis(d)), as a matrix mapping
// world p to (t.(p - c) sx + ox, b.(p - c) sx + ox, d.(p - c) sz, 1).
glm::mat4 ortho_light_matrix(const glm::vec3& d, const glm::vec3& c, float sx, float ox, float sz);

// The orthographic map's resolution for an image: `requested` if positive, else twice the image's
// larger side rounded up to a power of two, between 256 and 4096 (the map spans the whole scene,
// a cube face only 90 degrees of it).
int ortho_resolution_for(int requested, int width, int height);

} // namespace irad::gl
