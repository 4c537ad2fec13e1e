#pragma once
// The orthographic shadow maps of a batch of directions (directional and environment VPLs) in one
// 2D atlas, drawn by one instanced draw call (raster/glsl/ortho_atlas_shaders.h): each tile holds
// OrthoShadow's map of one direction (the same square over the scene's bounding sphere, the same
// M x M texels) as the window depth (z + 1) / 2 of a DEPTH_COMPONENT32F texture, z = d.(p - c) / h
// (c the bounds' centre, h the square's half width); the deferred passes read it as the depth
// (2 z_w - 1) h along d. Cleared to 1 (far: never shadowed).
#include "core/scene/bounds.h"
#include "raster/context/shader_program.h"
#include "raster/scene/gpu_scene.h"
#include "raster/scene/material_glsl.h"

#include <glm/glm.hpp>
#include <vector>

namespace irad::gl {

class OrthoAtlas {
public:
  // Room for `tiles` maps of resolution^2 texels; throws irad::Error when that exceeds this GL.
  OrthoAtlas(const GladGLContext& api, int resolution, int tiles, const Bounds& bounds,
             const MaterialFeatures& features);

  // The most tiles (<= wanted) of resolution^2 an atlas can hold on this GL (0: none fits).
  static int capacity(const GladGLContext& api, int resolution, int wanted);

  // Clears the atlas and draws the maps of directions[0..n) (unit, n <= tiles()). lookups[i]
  // receives direction i's world -> (u, v, depth along d) with u, v in [0, 1] over its tile,
  // origins[i] the tile's first texel. Changes the bound framebuffer, viewport and program.
  void render(const glm::vec3* directions, int n, const GpuScene& scene,
              std::vector<glm::mat4>& lookups, std::vector<glm::ivec2>& origins);

  GLuint texture() const { return atlas_[current_].get(); }
  int resolution() const { return resolution_; }
  int tiles() const { return grid_.x * grid_.y; }
  float half_width() const { return half_width_; }
  // Width of one texel in world units (OrthoShadow::texel).
  float texel() const { return 2.0f * half_width_ / static_cast<float>(resolution_); }

private:
  const GladGLContext* api_;
  int resolution_;
  glm::ivec2 grid_; // tiles per row, rows
  glm::vec3 centre_;
  float half_width_;
  ShaderProgram program_;
  MaterialUniforms material_;
  // Two atlases drawn into in turn (as ShadowAtlas: no wait for the passes reading the last).
  Texture atlas_[2];
  Framebuffer fbo_[2];
  int current_ = 0;
  Buffer block_;
  std::vector<float> block_data_;
};

} // namespace irad::gl
