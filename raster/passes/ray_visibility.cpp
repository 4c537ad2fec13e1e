#include "raster/passes/ray_visibility.h"

#include "core/util/error.h"
#include "raster/passes/deferred_shader.h"

#include <chrono>

namespace irad::gl {

RayVisibility::RayVisibility(const GladGLContext& api, VisibilityTracer tracer)
    : api_(&api), tracer_(std::move(tracer)) {
  if (!tracer_) throw Error("", "--visibility", "rays asked for without a ray tracer");
}

void RayVisibility::read(const GBuffer& gbuffer) {
  gbuffer.read(positions_, normals_);
  width_ = gbuffer.width();
  height_ = gbuffer.height();
  seconds_ = 0.0;
}

void RayVisibility::ensure_texture(int n, glm::ivec2 tile) {
  if (texture_ && size_ == tile && layers_ >= n) return;
  texture_ = make_texture(*api_);
  size_ = tile;
  layers_ = std::max(n, layers_);
  const GladGLContext& api = *api_;
  api.BindTexture(GL_TEXTURE_2D_ARRAY, texture_.get());
  api.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  api.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  api.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, 0);
  api.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_R8, tile.x, tile.y, layers_, 0, GL_RED,
                 GL_UNSIGNED_BYTE, nullptr);
  api.BindTexture(GL_TEXTURE_2D_ARRAY, 0);
}

GLuint RayVisibility::answer(const AtlasVpl* vpls, int n, int k, glm::ivec2 tile) {
  if (set_ == nullptr || positions_.empty())
    throw Error("", "raster", "visibility by rays asked before its G-buffer and VPLs");
  const auto t0 = std::chrono::steady_clock::now();
  vpls_.resize(static_cast<std::size_t>(n));
  sets_.resize(static_cast<std::size_t>(n));
  for (int r = 0; r < n; ++r) {
    vpls_[static_cast<std::size_t>(r)] = vpls[r].vpl;
    sets_[static_cast<std::size_t>(r)] = vpls[r].set;
  }
  bytes_.resize(static_cast<std::size_t>(n) * static_cast<std::size_t>(tile.x) *
                static_cast<std::size_t>(tile.y));
  VisibilityRequest request;
  request.width = width_;
  request.height = height_;
  request.positions = positions_.data();
  request.normals = normals_.data();
  request.set = set_;
  request.vpls = vpls_.data();
  request.sets = sets_.data();
  request.count = static_cast<std::size_t>(n);
  request.k = k;
  request.tile = tile;
  request.out = bytes_.data();
  tracer_(request);
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ensure_texture(n, tile);
  const GladGLContext& api = *api_;
  api.BindTexture(GL_TEXTURE_2D_ARRAY, texture_.get());
  api.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  api.TexSubImage3D(GL_TEXTURE_2D_ARRAY, 0, 0, 0, 0, tile.x, tile.y, n, GL_RED, GL_UNSIGNED_BYTE,
                    bytes_.data());
  api.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  api.BindTexture(GL_TEXTURE_2D_ARRAY, 0);
  return texture_.get();
}

} // namespace irad::gl
