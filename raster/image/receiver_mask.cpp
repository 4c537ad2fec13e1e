#include "raster/image/receiver_mask.h"

#include "raster/glsl/deferred_shaders.h"
#include "raster/glsl/shaders.h"

#include <string>

namespace irad::gl {

namespace {

constexpr GLint mask_gbuffer_unit = 3; // the G-buffer's position, normal and albedo from here

// Atlas pixel a lies in tile (a / tile) of set s = (s.x, s.y) and stands for image pixel
// k (a - s tile) + s (Interleaved::tile_projection); its depth tells that pixel's receiver.
std::string mask_fragment() {
  return std::string(R"(#version 330 core
uniform sampler2D u_position;
uniform sampler2D u_albedo; // w: 1 where the BRDF is not Lambertian (raster/glsl/shaders.h)
uniform int u_k;
uniform ivec2 u_tile;
uniform ivec2 u_size;
const float LAMBERTIAN_DEPTH = )") +
         std::to_string(shaders::kLambertianReceiverDepth) + R"(;
const float GLOSSY_DEPTH = )" +
         std::to_string(shaders::kGlossyReceiverDepth) + R"(;
void main() {
  ivec2 a = ivec2(gl_FragCoord.xy), s = a / u_tile;
  ivec2 p = (a - s * u_tile) * u_k + s;
  if (p.x >= u_size.x || p.y >= u_size.y || texelFetch(u_position, p, 0).w <= 0.0) discard;
  gl_FragDepth = texelFetch(u_albedo, p, 0).w < 0.5 ? LAMBERTIAN_DEPTH : GLOSSY_DEPTH;
}
)";
}

} // namespace

ReceiverMask::ReceiverMask(const GladGLContext& api, GLuint atlas, int k, glm::ivec2 tile,
                           const GBuffer& gbuffer)
    : api_(&api), k_(k), tile_(tile), gbuffer_(&gbuffer), depth_(make_renderbuffer(api)),
      fbo_(make_framebuffer(api)), empty_vao_(make_vertex_array(api)),
      program_(api, "receiver mask", shaders::fullscreen_vertex, mask_fragment()) {
  api.BindRenderbuffer(GL_RENDERBUFFER, depth_.get());
  api.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, k * tile.x, k * tile.y);
  api.BindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, atlas, 0);
  api.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.get());
  check_framebuffer(api, "receiver mask framebuffer");
  program_.use();
  api.Uniform1i(program_.uniform("u_position"), mask_gbuffer_unit);
  api.Uniform1i(program_.uniform("u_albedo"), mask_gbuffer_unit + 2);
  api.Uniform1i(program_.uniform("u_k"), k);
  api.Uniform2i(program_.uniform("u_tile"), tile.x, tile.y);
  api.Uniform2i(program_.uniform("u_size"), gbuffer.width(), gbuffer.height());
}

void ReceiverMask::mark() {
  const GladGLContext& api = *api_;
  api.BindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  api.Viewport(0, 0, k_ * tile_.x, k_ * tile_.y);
  api.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  api.DepthMask(GL_TRUE);
  api.ClearDepth(1.0);
  api.Clear(GL_DEPTH_BUFFER_BIT);
  api.Enable(GL_DEPTH_TEST);
  api.DepthFunc(GL_ALWAYS);
  api.Disable(GL_BLEND);
  program_.use();
  gbuffer_->bind_textures(mask_gbuffer_unit);
  api.BindVertexArray(empty_vao_.get());
  api.DrawArrays(GL_TRIANGLES, 0, 3);
  api.DepthFunc(GL_LESS);
  api.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void ReceiverMask::bind_tile(int set) const {
  api_->BindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  api_->Viewport((set % k_) * tile_.x, (set / k_) * tile_.y, tile_.x, tile_.y);
}

} // namespace irad::gl
