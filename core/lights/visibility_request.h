#pragma once
// Visibility by rays for the raster (RasterOptions::visibility): instead of drawing shadow maps,
// the raster hands a ray tracer the G-buffer it shades and a batch of VPLs, and reads back per
// VPL and pixel whether the VPL lights the pixel's surface at all, its shadow ray unblocked
// (walk/estimators/visibility_tracer.h answers; the raster itself never links a ray tracer). The
// shading maths stays the raster's: this answers V(y, x) alone, as rt-vpl's shadow rays do.
#include "core/lights/vpl.h"

#include <cstdint>
#include <functional>
#include <glm/glm.hpp>

namespace irad {

struct VisibilityRequest {
  // The G-buffer, row by row from the bottom (texel (x, y) at y * width + x): world positions
  // (w > 0 on a surface) and normals towards the camera.
  int width = 0, height = 0;
  const glm::vec4* positions = nullptr;
  const glm::vec4* normals = nullptr;
  // The VPL set the records come from (its lobes and mirror polygons), and the records: VPL r
  // lights the pixels k t + (sets[r] mod k, sets[r] / k) of its interleaved set's tile, t in
  // [0, tile.x) x [0, tile.y) (k = 1: the whole image, sets 0).
  const VplSet* set = nullptr;
  const Vpl* const* vpls = nullptr;
  const int* sets = nullptr;
  std::size_t count = 0;
  int k = 1;
  glm::ivec2 tile{0};
  // count x tile.y x tile.x bytes, record by record: 255 where the VPL's light reaches the
  // pixel's surface (its term nonzero and its shadow ray unblocked), else 0; 0 too for tile
  // pixels outside the image or off every surface.
  std::uint8_t* out = nullptr;
};

// Fills request.out; called on the raster's thread, free to use every core.
using VisibilityTracer = std::function<void(const VisibilityRequest&)>;

} // namespace irad
