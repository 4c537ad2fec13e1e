#include "raster/image/edge_pixels.h"

#include "raster/glsl/shaders.h"

#include <algorithm>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

namespace irad::gl {

namespace {

constexpr GLint gbuffer_unit = 3;      // position, normal (and albedo) at 3, 4, 5
constexpr GLint unsure_atlas_unit = 2; // the interleaved atlas (unsure pixels)

// 1 where some pixel of the window -h..h around p does not show p's surface
// (shaders::resolve_window_glsl), 0 elsewhere and on the background.
constexpr const char* mark_fragment = R"(#version 330 core
uniform sampler2D u_position;
uniform sampler2D u_normal;
uniform ivec2 u_size;
uniform int u_h;
out vec4 o_mask;
#pragma irad_resolve_window
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 xp = texelFetch(u_position, p, 0);
  float edge = 0.0;
  if (xp.w > 0.0) {
    vec3 np = texelFetch(u_normal, p, 0).xyz;
    for (int dy = -u_h; dy <= u_h; ++dy)
      for (int dx = -u_h; dx <= u_h; ++dx)
        if (!same_surface(p + ivec2(dx, dy), xp.xyz, np)) edge = 1.0;
  }
  o_mask = vec4(edge);
}
)";

// 1 where the light of the VPLs whose shadow lookup was unsure (the interleaved atlas's alpha,
// raster/glsl/cube_glsl.h lookup_unsure) is at least u_share of the light the pixel's own set
// gave it (the atlas's rgb, de-interleaved as the resolve does), 0 elsewhere and on the background.
constexpr const char* unsure_fragment = R"(#version 330 core
uniform sampler2D u_position;
uniform sampler2D u_atlas;
uniform int u_k;
uniform ivec2 u_tile;
uniform float u_share;
out vec4 o_mask;
#pragma irad_luminance
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float unsure = 0.0;
  if (texelFetch(u_position, p, 0).w > 0.0) {
    vec4 a = texelFetch(u_atlas, (p % u_k) * u_tile + p / u_k, 0);
    if (a.a > 0.0 && a.a >= u_share * dot(a.rgb, LUMINANCE)) unsure = 1.0;
  }
  o_mask = vec4(unsure);
}
)";

// The unsure pass's source, the luminance weights inserted.
std::string unsure_source() {
  std::string s = unsure_fragment;
  insert_glsl(s, "#pragma irad_luminance\n", shaders::luminance_glsl);
  return s;
}

// Defines `texture` as an RG32I texture of width x height holding `texels` (2 per texel),
// nearest filtering, no mipmaps (an integer texture needs that to be complete).
void upload_pairs(const GladGLContext& api, GLuint texture, int width, int height,
                  const std::vector<GLint>& texels) {
  api.BindTexture(GL_TEXTURE_2D, texture);
  api.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  api.TexImage2D(GL_TEXTURE_2D, 0, GL_RG32I, width, height, 0, GL_RG_INTEGER, GL_INT,
                 texels.data());
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  api.BindTexture(GL_TEXTURE_2D, 0);
}

} // namespace

std::string with_resolve_window(const char* source) {
  std::string s = source;
  insert_glsl(s, "#pragma irad_resolve_window\n", shaders::resolve_window_glsl);
  return s;
}

EdgePixels::EdgePixels(const GladGLContext& api, int k, const GBuffer& gbuffer, bool unsure)
    : api_(&api), width_(gbuffer.width()), height_(gbuffer.height()), gbuffer_(&gbuffer),
      mask_(make_float_texture(api, width_, height_, GL_R8, GL_RED)),
      mask_fbo_(make_framebuffer(api)), list_(make_texture(api)), texel_of_(make_texture(api)),
      light_fbo_(make_framebuffer(api)), empty_vao_(make_vertex_array(api)),
      mark_(api, "edge pixels", shaders::fullscreen_vertex, with_resolve_window(mark_fragment)),
      unsure_(unsure ? std::make_unique<ShaderProgram>(api, "unsure pixels",
                                                       shaders::fullscreen_vertex, unsure_source())
                     : nullptr) {
  api.BindFramebuffer(GL_FRAMEBUFFER, mask_fbo_.get());
  api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, mask_.get(), 0);
  check_framebuffer(api, "edge mask framebuffer");
  api.BindFramebuffer(GL_FRAMEBUFFER, 0);
  mark_.use();
  api.Uniform1i(mark_.uniform("u_position"), gbuffer_unit);
  api.Uniform1i(mark_.uniform("u_normal"), gbuffer_unit + 1);
  api.Uniform2i(mark_.uniform("u_size"), width_, height_);
  api.Uniform1i(mark_.uniform("u_h"), k / 2);
  api.Uniform1f(mark_.uniform("u_depth"), 0.0f);
  if (!unsure_) return;
  unsure_->use();
  api.Uniform1i(unsure_->uniform("u_position"), gbuffer_unit);
  api.Uniform1i(unsure_->uniform("u_atlas"), unsure_atlas_unit);
  api.Uniform1i(unsure_->uniform("u_k"), k);
  api.Uniform1f(unsure_->uniform("u_share"), kUnsureShare);
  api.Uniform1f(unsure_->uniform("u_depth"), 0.0f);
}

std::vector<glm::ivec2> EdgePixels::marked(const ShaderProgram& mark) {
  const GladGLContext& api = *api_;
  api.BindFramebuffer(GL_FRAMEBUFFER, mask_fbo_.get());
  api.Viewport(0, 0, width_, height_);
  api.Disable(GL_DEPTH_TEST);
  api.Disable(GL_BLEND);
  mark.use();
  gbuffer_->bind_textures(gbuffer_unit);
  api.BindVertexArray(empty_vao_.get());
  api.DrawArrays(GL_TRIANGLES, 0, 3);
  std::vector<unsigned char> mask(static_cast<std::size_t>(width_) * height_);
  api.BindFramebuffer(GL_READ_FRAMEBUFFER, mask_fbo_.get());
  api.ReadBuffer(GL_COLOR_ATTACHMENT0);
  api.PixelStorei(GL_PACK_ALIGNMENT, 1);
  api.ReadPixels(0, 0, width_, height_, GL_RED, GL_UNSIGNED_BYTE, mask.data());
  api.BindFramebuffer(GL_FRAMEBUFFER, 0);
  std::vector<glm::ivec2> pixels;
  for (std::size_t i = 0; i < mask.size(); ++i)
    if (mask[i] != 0)
      pixels.emplace_back(static_cast<int>(i % width_), static_cast<int>(i / width_));
  return pixels;
}

void EdgePixels::find(bool shaded) {
  pixels_ = marked(mark_);
  edges_ = pixels_.size();
  if (shaded) upload();
}

void EdgePixels::add_unsure(GLuint atlas, glm::ivec2 tile) {
  if (!unsure_) return;
  unsure_->use();
  api_->Uniform2i(unsure_->uniform("u_tile"), tile.x, tile.y);
  api_->ActiveTexture(GL_TEXTURE0 + unsure_atlas_unit);
  api_->BindTexture(GL_TEXTURE_2D, atlas);
  const std::vector<glm::ivec2> unsure = marked(*unsure_);
  // Both lists are row-major: their union, in that order.
  const auto row_major = [](glm::ivec2 a, glm::ivec2 b) {
    return a.y != b.y ? a.y < b.y : a.x < b.x;
  };
  std::vector<glm::ivec2> all;
  all.reserve(pixels_.size() + unsure.size());
  std::set_union(pixels_.begin(), pixels_.end(), unsure.begin(), unsure.end(),
                 std::back_inserter(all), row_major);
  pixels_ = std::move(all);
}

void EdgePixels::upload() {
  const GladGLContext& api = *api_;
  // The list, row-major over the image; each pixel's texel in it.
  rows_ = std::max(1, static_cast<int>((pixels_.size() + width_ - 1) / width_));
  std::vector<GLint> list(static_cast<std::size_t>(width_) * rows_ * 2, -1);
  std::vector<GLint> texel_of(static_cast<std::size_t>(width_) * height_ * 2, -1);
  for (std::size_t n = 0; n < pixels_.size(); ++n) {
    const glm::ivec2 p = pixels_[n];
    list[2 * n] = p.x;
    list[2 * n + 1] = p.y;
    const std::size_t i = static_cast<std::size_t>(p.y) * width_ + p.x;
    texel_of[2 * i] = static_cast<GLint>(n % width_);
    texel_of[2 * i + 1] = static_cast<GLint>(n / width_);
  }
  upload_pairs(api, list_.get(), width_, rows_, list);
  upload_pairs(api, texel_of_.get(), width_, height_, texel_of);
  light_ = make_float_texture(api, width_, rows_);
  api.BindFramebuffer(GL_FRAMEBUFFER, light_fbo_.get());
  api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, light_.get(), 0);
  check_framebuffer(api, "edge light framebuffer");
  api.Viewport(0, 0, width_, rows_);
  api.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  api.Clear(GL_COLOR_BUFFER_BIT);
  api.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

void EdgePixels::bind_light() const {
  api_->BindFramebuffer(GL_FRAMEBUFFER, light_fbo_.get());
  api_->Viewport(0, 0, width_, rows_);
}

} // namespace irad::gl
