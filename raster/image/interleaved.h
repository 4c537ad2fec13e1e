#pragma once
// Interleaved sampling (Keller & Heidrich 2001) for the VPL passes: the VPLs are split into k x k
// sets, and set (dx, dy) lights only the pixels (x, y) with x mod k = dx, y mod k = dy. Those
// pixels form a (W/k) x (H/k) sub-image, rendered as one tile of a de-interleaved atlas with a
// projection shifted by the set's sub-pixel offset, so a VPL pass shades 1/k^2 of the pixels.
// A resolve pass re-interleaves the atlas and averages the k^2 sets over each k x k window with a
// geometry-aware filter (raster/glsl/shaders.h resolve_fragment).
#include "raster/context/gl_objects.h"
#include "raster/context/shader_program.h"

#include <glm/glm.hpp>

namespace irad::gl {

class Interleaved {
public:
  // depth: the full-resolution target's depth renderbuffer, shared with the G-buffer pass.
  Interleaved(const GladGLContext& api, int width, int height, int k, GLuint depth);

  int k() const { return k_; }
  int sets() const { return k_ * k_; }
  // Full-resolution G-buffer (position, normal, albedo): bound with the viewport set.
  void bind_gbuffer() const;
  // The atlas with the viewport on one set's tile (set in [0, k^2)), or on the whole atlas.
  void bind_tile(int set) const;
  void bind_atlas() const;
  // The camera projection moved so that tile pixel (X, Y) of `set` sees the centre of full-image
  // pixel (k X + dx, k Y + dy).
  glm::mat4 tile_projection(int set, const glm::mat4& projection) const;
  // Writes the resolved VPL light into the bound framebuffer (full resolution, no blending).
  void resolve() const;

private:
  const GladGLContext* api_;
  int width_, height_, k_, tile_w_, tile_h_;
  Texture position_, normal_, albedo_, atlas_;
  Renderbuffer atlas_depth_;
  Framebuffer gbuffer_fbo_, atlas_fbo_;
  VertexArray empty_vao_;
  ShaderProgram resolve_;
};

} // namespace irad::gl
