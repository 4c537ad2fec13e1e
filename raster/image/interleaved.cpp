#include "raster/image/interleaved.h"

#include "core/util/error.h"
#include "raster/glsl/shaders.h"

namespace irad::gl {

namespace {

// The G-buffer's position, normal and albedo at position_unit, + 1, + 2; the edge pixels'
// texels and light after them.
constexpr GLint atlas_unit = 2, position_unit = 3, edge_at_unit = 6, edge_light_unit = 7;

} // namespace

Interleaved::Interleaved(const GladGLContext& api, int k, const GBuffer& gbuffer, bool find_edges,
                         bool shade_edges)
    : api_(&api), width_(gbuffer.width()), height_(gbuffer.height()), k_(k),
      tile_w_((width_ + k - 1) / k), tile_h_((height_ + k - 1) / k), gbuffer_(&gbuffer),
      atlas_(make_float_texture(api, k * tile_w_, k * tile_h_)),
      atlas_depth_(make_renderbuffer(api)), atlas_fbo_(make_framebuffer(api)),
      empty_vao_(make_vertex_array(api)),
      edges_((find_edges || shade_edges) && k > 1
                 ? std::make_unique<EdgePixels>(api, k, gbuffer, find_edges && !shade_edges)
                 : nullptr),
      receivers_(gbuffer.glossy() ? std::make_unique<ReceiverMask>(
                                        api, atlas_.get(), k, glm::ivec2(tile_w_, tile_h_), gbuffer)
                                  : nullptr),
      shade_edges_(shade_edges), resolve_(api, "resolve", shaders::fullscreen_vertex,
                                          with_resolve_window(shaders::resolve_fragment)),
      scale_location_(resolve_.uniform("u_scale")), edges_location_(resolve_.uniform("u_edges")) {
  if (k < 1) throw Error("", "--interleave", "must be at least 1");
  api.BindRenderbuffer(GL_RENDERBUFFER, atlas_depth_.get());
  api.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, k * tile_w_, k * tile_h_);
  api.BindFramebuffer(GL_FRAMEBUFFER, atlas_fbo_.get());
  api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, atlas_.get(), 0);
  api.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                              atlas_depth_.get());
  check_framebuffer(api, "interleaved atlas framebuffer");

  resolve_.use();
  api.Uniform1i(resolve_.uniform("u_atlas"), atlas_unit);
  api.Uniform1i(resolve_.uniform("u_position"), position_unit);
  api.Uniform1i(resolve_.uniform("u_normal"), position_unit + 1);
  api.Uniform1i(resolve_.uniform("u_albedo"), position_unit + 2);
  api.Uniform1i(resolve_.uniform("u_k"), k);
  api.Uniform2i(resolve_.uniform("u_tile"), tile_w_, tile_h_);
  api.Uniform2i(resolve_.uniform("u_size"), width_, height_);
  api.Uniform1i(resolve_.uniform("u_edge_at"), edge_at_unit);
  api.Uniform1i(resolve_.uniform("u_edge_light"), edge_light_unit);
}

void Interleaved::bind_tile(int set, bool receivers) const {
  if (receivers && receivers_) {
    receivers_->bind_tile(set);
    return;
  }
  api_->BindFramebuffer(GL_FRAMEBUFFER, atlas_fbo_.get());
  api_->Viewport((set % k_) * tile_w_, (set / k_) * tile_h_, tile_w_, tile_h_);
}

void Interleaved::bind_atlas() const {
  api_->BindFramebuffer(GL_FRAMEBUFFER, atlas_fbo_.get());
  api_->Viewport(0, 0, k_ * tile_w_, k_ * tile_h_);
}

glm::mat4 Interleaved::tile_projection(int set, const glm::mat4& projection) const {
  // Tile coordinate X maps to image coordinate g = k X + c with c = d + 1/2 - k/2 (pixel units),
  // so image NDC n and tile NDC m satisfy m = a n + b with a = W / (k w), b = (1 - 2c/W) a - 1.
  const auto axis = [&](int d, int size, int tile) {
    const double c = d + 0.5 - 0.5 * k_;
    const double a = static_cast<double>(size) / (static_cast<double>(k_) * tile);
    return glm::vec2(static_cast<float>(a), static_cast<float>((1.0 - 2.0 * c / size) * a - 1.0));
  };
  const glm::vec2 x = axis(set % k_, width_, tile_w_), y = axis(set / k_, height_, tile_h_);
  glm::mat4 shift(1.0f);
  shift[0][0] = x.x;
  shift[3][0] = x.y;
  shift[1][1] = y.x;
  shift[3][1] = y.y;
  return shift * projection;
}

void Interleaved::resolve(const std::vector<float>& scales, bool use_edges) const {
  if (scales.size() != static_cast<std::size_t>(sets()))
    throw Error("interleaved resolve: " + std::to_string(scales.size()) + " scales for " +
                std::to_string(sets()) + " sets");
  api_->Disable(GL_DEPTH_TEST);
  api_->Disable(GL_BLEND);
  resolve_.use();
  api_->Uniform1fv(scale_location_, sets(), scales.data());
  const EdgePixels* e = use_edges ? shaded_edges() : nullptr;
  api_->Uniform1i(edges_location_, e ? 1 : 0);
  if (e) {
    api_->ActiveTexture(GL_TEXTURE0 + edge_at_unit);
    api_->BindTexture(GL_TEXTURE_2D, e->texel_of());
    api_->ActiveTexture(GL_TEXTURE0 + edge_light_unit);
    api_->BindTexture(GL_TEXTURE_2D, e->light());
  }
  api_->ActiveTexture(GL_TEXTURE0 + atlas_unit);
  api_->BindTexture(GL_TEXTURE_2D, atlas_.get());
  gbuffer_->bind_textures(position_unit);
  api_->BindVertexArray(empty_vao_.get());
  api_->DrawArrays(GL_TRIANGLES, 0, 3);
}

} // namespace irad::gl
