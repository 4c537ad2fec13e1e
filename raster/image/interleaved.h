#pragma once
// Interleaved sampling (Keller & Heidrich 2001) for the VPL passes: the VPLs are split into k x k
// sets, and set (dx, dy) lights only the pixels (x, y) with x mod k = dx, y mod k = dy. Those
// pixels form a (W/k) x (H/k) sub-image, rendered as one tile of a de-interleaved atlas with a
// projection shifted by the set's sub-pixel offset, so a VPL pass shades 1/k^2 of the pixels.
// A resolve pass re-interleaves the atlas and averages the k^2 sets over each k x k window with a
// geometry-aware filter (raster/glsl/shaders.h resolve_fragment). The pixels where that window
// is cut (raster/image/edge_pixels.h) may be listed for the caller, or shaded by every set and
// keep their own sum.
#include "raster/context/gl_objects.h"
#include "raster/context/shader_program.h"
#include "raster/image/edge_pixels.h"
#include "raster/image/gbuffer.h"
#include "raster/image/receiver_mask.h"

#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace irad::gl {

class Interleaved {
public:
  // gbuffer: the image's (its size is the image's), read by the resolve; kept by reference.
  // find_edges: whether each image lists its edge pixels (EdgePixels); shade_edges: whether the
  // deferred passes shade them with every set and the resolve keeps their sums.
  Interleaved(const GladGLContext& api, int k, const GBuffer& gbuffer, bool find_edges,
              bool shade_edges);

  int k() const { return k_; }
  int sets() const { return k_ * k_; }
  // The atlas with the viewport on one set's tile (set in [0, k^2)), or on the whole atlas.
  // receivers: with the receiver mask as its depth (has_receiver_mask()).
  void bind_tile(int set, bool receivers = false) const;
  void bind_atlas() const;
  // The camera projection moved so that tile pixel (X, Y) of `set` sees the centre of full-image
  // pixel (k X + dx, k Y + dy).
  glm::mat4 tile_projection(int set, const glm::mat4& projection) const;
  // The tile's rectangle in the atlas (x, y, w, h) of `set`.
  glm::ivec4 tile(int set) const {
    return {(set % k_) * tile_w_, (set / k_) * tile_h_, tile_w_, tile_h_};
  }
  // With edge pixels: finds this image's from the G-buffer as it is now (after its pass).
  void find_edges() {
    if (edges_) edges_->find(shade_edges_);
  }
  // A glossy G-buffer's receiver mask (raster/image/receiver_mask.h): marks its Lambertian and
  // glossy pixels, after its pass (each image's, before the deferred passes read the mask).
  void mark_receivers() {
    if (receivers_) receivers_->mark();
  }
  bool has_receiver_mask() const { return receivers_ != nullptr; }
  // With find_edges (and not shade_edges), after the shading: adds the unsure pixels to the
  // list (EdgePixels::add_unsure; the deferred passes must have written the unsure light).
  void find_unsure() {
    if (edges_) edges_->add_unsure(atlas_.get(), {tile_w_, tile_h_});
  }
  // This image's edge pixels (nullptr without).
  const EdgePixels* edges() const { return edges_.get(); }
  // The edge pixels the deferred passes shade with every set; nullptr without, or with none.
  const EdgePixels* shaded_edges() const {
    return shade_edges_ && edges_ && edges_->count() > 0 ? edges_.get() : nullptr;
  }
  // Writes the resolved VPL light into the bound framebuffer (full resolution, no blending), set s
  // scaled by scales[s] (core/lights/interleave_sets.h; sets() of them). use_edges: the edge pixels
  // take their own sums (every VPL of the image was shaded into them).
  void resolve(const std::vector<float>& scales, bool use_edges) const;

private:
  const GladGLContext* api_;
  int width_, height_, k_, tile_w_, tile_h_;
  const GBuffer* gbuffer_;
  Texture atlas_;
  Renderbuffer atlas_depth_;
  Framebuffer atlas_fbo_;
  VertexArray empty_vao_;
  std::unique_ptr<EdgePixels> edges_;
  std::unique_ptr<ReceiverMask> receivers_; // a glossy G-buffer's
  bool shade_edges_;
  ShaderProgram resolve_;
  GLint scale_location_, edges_location_; // u_scale (the sets' scales), u_edges
};

} // namespace irad::gl
