#pragma once
// Which interleaved atlas pixels see a glossy receiver, as a depth buffer the deferred passes
// test (raster/passes/deferred_shader.h): llvmpipe runs every branch of a fragment shader under a
// mask, so the receiver's BRDF costs each pixel it shades, Lambertian or not, while an early
// depth test that fails for a whole group of pixels skips the shader there. In a glossy scene
// each tile pixel of the atlas (raster/image/interleaved.h) gets the depth
// shaders::kLambertianReceiverDepth where its G-buffer pixel is Lambertian,
// shaders::kGlossyReceiverDepth where it is not, and 1 where it sees no surface; the deferred
// passes then draw the Lambertian pixels with a program without the receiver's BRDF and the
// glossy ones with it, each at its depth with GL_EQUAL, and the background with neither.
#include "raster/context/gl_objects.h"
#include "raster/context/shader_program.h"
#include "raster/image/gbuffer.h"

namespace irad::gl {

class ReceiverMask {
public:
  // Over the atlas texture `atlas` (k x k tiles of tile.x x tile.y pixels), for the pixels of
  // `gbuffer` (glossy; kept by reference).
  ReceiverMask(const GladGLContext& api, GLuint atlas, int k, glm::ivec2 tile,
               const GBuffer& gbuffer);

  // Marks the G-buffer's pixels as it is now (after its pass).
  void mark();
  // The atlas with this mask as its depth, the viewport on one set's tile.
  void bind_tile(int set) const;

private:
  const GladGLContext* api_;
  int k_;
  glm::ivec2 tile_;
  const GBuffer* gbuffer_;
  Renderbuffer depth_;
  Framebuffer fbo_;
  VertexArray empty_vao_;
  ShaderProgram program_;
};

} // namespace irad::gl
