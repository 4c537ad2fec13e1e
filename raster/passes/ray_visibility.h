#pragma once
// Visibility by rays for the batched passes (RasterOptions::visibility): instead of a shadow
// atlas per batch, each shading upload's VPLs are answered by the caller's ray tracer
// (core/lights/visibility_request.h) over the tile pixels they shade, and the answers go to a
// 2D array texture that the deferred shader reads in place of every shadow lookup
// (raster/glsl/deferred_shaders.h IRAD_RAYS). The G-buffer is read back once per image for it.
// No shadow map, hierarchy or helper thread is made: on a CPU renderer (llvmpipe) one shadow ray
// per VPL and shaded pixel costs less than the VPL's shadow faces (docs/performance.md
// "Visibility by rays").
#include "core/lights/visibility_request.h"
#include "raster/context/gl_objects.h"
#include "raster/image/gbuffer.h"

#include <glm/glm.hpp>
#include <vector>

namespace irad::gl {

struct AtlasVpl;

class RayVisibility {
public:
  RayVisibility(const GladGLContext& api, VisibilityTracer tracer);

  // The G-buffer the next answers are for (read back here); seconds() starts again.
  void read(const GBuffer& gbuffer);
  // The set the next answers' VPLs belong to (its lobes and mirrors); not owned.
  void set_vpls(const VplSet* set) { set_ = set; }
  // vpls[0..n) answered over the tile pixels of their sets (k x k interleaving, tiles of `tile`
  // pixels; k = 1: the image) and uploaded, layer r for vpls[r]; returns the texture.
  GLuint answer(const AtlasVpl* vpls, int n, int k, glm::ivec2 tile);
  // Seconds spent in the tracer since read().
  double seconds() const { return seconds_; }

private:
  // The texture for at least n layers of `tile`.
  void ensure_texture(int n, glm::ivec2 tile);

  const GladGLContext* api_;
  VisibilityTracer tracer_;
  std::vector<glm::vec4> positions_, normals_;
  int width_ = 0, height_ = 0;
  const VplSet* set_ = nullptr;
  std::vector<const Vpl*> vpls_;
  std::vector<int> sets_;
  std::vector<std::uint8_t> bytes_;
  Texture texture_;
  glm::ivec2 size_{0};
  int layers_ = 0;
  double seconds_ = 0.0;
};

} // namespace irad::gl
