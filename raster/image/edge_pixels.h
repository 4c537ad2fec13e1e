#pragma once
// The pixels whose interleaved resolve window is cut (raster/image/interleaved.h): some pixel of
// the k x k window around them shows another surface (a crease, a step, a silhouette) or lies
// off the image. There the resolve can only fill the missing sets in from one side, a blur that
// does not average away over rounds: on the Cornell box (256x256, k = 2, 4 rounds) the crease
// rows come out 2-5 % brighter than with every VPL shading every pixel. With edge pixels the
// deferred passes shade these pixels with every set (k^2 times a tile pixel's work) and the
// resolve keeps their own sum, k = 1's value.
//
// What it buys depends on the scene (docs/accuracy.md): per pixel it always helps
// (zdm2 at 128x128: relMSE 7.45e-3 -> 4.88e-3 for 3-5 % more time; the Cornell box 4.36e-4 ->
// 4.02e-4 for 30 % more); per 4x4 block it gains on zdm2 (1.65e-3 -> 1.34e-3), little on the
// Cornell box, and loses on godot (1.40e-3 -> 1.59e-3), whose contact shadows the shadow maps
// darken: the one-sided blur lifts them. So shading them is an option (--interleave-edges
// shaded). The default from 2 rounds on only lists them (RasterOptions::edge_pixels Listed) and
// lib/render.cpp traces them over the same VPLs, which also removes the shadow maps' error there.
//
// With the listing, the pixels whose shadow lookups could not decide a tenth of their light or
// more (the unsure pixels: a silhouette's penumbra or a contact within a texel, as the VPL's map
// sees it) are listed too, after the shading, so that lib/render.cpp traces them as well.
//
// Per image: one pass over the G-buffer marks them, the mask is read back, and their coordinates
// are packed into a list texture (W texels wide, row-major, (-1, -1) past the last), which the
// deferred passes draw over (TilePixels::list). A full-resolution texture maps each pixel to its
// texel in the list (the resolve's lookup).
#include "raster/context/gl_objects.h"
#include "raster/context/shader_program.h"
#include "raster/image/gbuffer.h"

#include <cstddef>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

namespace irad::gl {

// `source` with its "#pragma irad_resolve_window" line replaced by shaders::resolve_window_glsl
// (the resolve's and the edge pass's window).
std::string with_resolve_window(const char* source);

// A listed pixel is unsure when the VPLs whose shadow lookups could not decide it (the shading's
// alpha: raster/glsl/cube_glsl.h lookup_unsure) carry at least this share of the light its set
// gave it. Measured (one round, k = 2, 4x4-block relMSE against rt-vpl over the same VPLs, the
// unsure pixels given rt-vpl's values): godot 128x128, share 0.05 / 0.1 / 0.2: 21 / 12 / 6 % of
// the pixels beyond the edge pixels, 2.07e-4 -> 2.4e-5 / 4.2e-5 / 6.7e-5; the Cornell box
// 256x256: 10 / 7.4 / 4.1 %, 1.26e-5 -> 2.7e-6 / 3.1e-6 / 4.1e-6.
inline constexpr float kUnsureShare = 0.1f;

class EdgePixels {
public:
  // For the resolve window of `k` (> 1) over `gbuffer`'s image (kept by reference); unsure:
  // add_unsure() can list the unsure pixels too.
  EdgePixels(const GladGLContext& api, int k, const GBuffer& gbuffer, bool unsure = false);

  // Marks the edge pixels of the G-buffer as it is now and lists them; for shading (`shaded`)
  // uploads the list and clears their light. Leaves the draw framebuffer unbound.
  void find(bool shaded);
  // After the shading into the interleaved `atlas` (tiles of `tile` texels; its alpha the unsure
  // light, raster/passes/deferred_shader.h): adds the unsure pixels (kUnsureShare) to the list
  // (only for listing: the list is not uploaded again). Nothing without `unsure`.
  void add_unsure(GLuint atlas, glm::ivec2 tile);
  // The pixels the last find() and add_unsure() listed, row by row.
  const std::vector<glm::ivec2>& pixels() const { return pixels_; }
  std::size_t count() const { return pixels_.size(); }
  // Of them, the edge pixels; the rest are unsure.
  std::size_t edge_count() const { return edges_; }
  // The list's light as the draw framebuffer, the viewport on the list's rows.
  void bind_light() const;
  // The list's (RG32I) texel p holds the image pixel it stands for.
  GLuint list() const { return list_.get(); }
  // Full resolution, RG32I: each pixel's texel in the light texture, (-1, -1) off the list.
  GLuint texel_of() const { return texel_of_.get(); }
  GLuint light() const { return light_.get(); }

private:
  // The list, the pixels' texels in it, and their light cleared (shading).
  void upload();
  // Draws `mark` into the mask and lists the pixels it marked, row by row.
  std::vector<glm::ivec2> marked(const ShaderProgram& mark);

  const GladGLContext* api_;
  int width_, height_;
  const GBuffer* gbuffer_;
  std::vector<glm::ivec2> pixels_;
  std::size_t edges_ = 0;
  int rows_ = 0; // of the list in use
  Texture mask_;
  Framebuffer mask_fbo_;
  Texture list_, texel_of_, light_;
  Framebuffer light_fbo_;
  VertexArray empty_vao_;
  ShaderProgram mark_;
  std::unique_ptr<ShaderProgram> unsure_;
};

} // namespace irad::gl
