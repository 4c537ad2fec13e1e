#include "raster/shadow/ortho_atlas.h"

#include "core/util/error.h"
#include "raster/glsl/batched_shaders.h"
#include "raster/glsl/ortho_atlas_shaders.h"
#include "raster/shadow/ortho_shadow.h"
#include "raster/shadow/shadow_atlas.h"

#include <algorithm>
#include <cstring>
#include <string>

namespace irad::gl {

namespace {

constexpr GLuint kOrthoBlockBinding = 2;
// The OrthoBatch block per direction (std140): a mat4 and two vec4.
constexpr int kBytesPerTile = 64 + 16 + 16;

// Tiles per row and rows for n tiles, as square as the side allows.
glm::ivec2 tile_grid(int n, int per_side) {
  const int columns = std::min(per_side, static_cast<int>(std::ceil(std::sqrt(double(n)))));
  return {columns, (n + columns - 1) / columns};
}

} // namespace

int OrthoAtlas::capacity(const GladGLContext& api, int resolution, int wanted) {
  GLint uniform_block = 0;
  api.GetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &uniform_block);
  const int per_side = max_atlas_side(api) / std::max(resolution, 1);
  return std::min({wanted, per_side * per_side, static_cast<int>(uniform_block) / kBytesPerTile});
}

OrthoAtlas::OrthoAtlas(const GladGLContext& api, int resolution, int tiles, const Bounds& bounds,
                       const MaterialFeatures& features)
    : api_(&api), resolution_(resolution),
      grid_(tile_grid(std::max(tiles, 1),
                      std::max(max_atlas_side(api) / std::max(resolution, 1), 1))),
      centre_(bounds.center()), half_width_(ortho_half_width(bounds)),
      program_(
          api, "ortho atlas",
          material_source(shaders::batched_source(shaders::ortho_atlas_vertex, tiles), features),
          material_source(shaders::batched_source(shaders::ortho_atlas_fragment, tiles), features)),
      material_(program_), block_(make_buffer(api)),
      block_data_(static_cast<std::size_t>(tiles) * kBytesPerTile / sizeof(float), 0.0f) {
  if (tiles < 1 || capacity(api, resolution, tiles) < tiles)
    throw Error("", "orthographic shadow atlas",
                std::to_string(tiles) + " maps of " + std::to_string(resolution) +
                    "^2 do not fit this OpenGL");
  const glm::ivec2 size = grid_ * resolution;
  for (int a = 0; a < 2; ++a) {
    atlas_[a] = make_depth_texture(api, size.x, size.y);
    fbo_[a] = make_depth_framebuffer(api, atlas_[a].get(), "orthographic shadow atlas framebuffer");
  }
  const GLuint index = api.GetUniformBlockIndex(program_.get(), "OrthoBatch");
  if (index == GL_INVALID_INDEX) throw Error("", "shader ortho atlas", "no block OrthoBatch");
  api.UniformBlockBinding(program_.get(), index, kOrthoBlockBinding);
  program_.use();
  api.Uniform1f(program_.uniform("u_tile_size"), static_cast<float>(resolution));
  api.Uniform2f(program_.uniform("u_atlas_size"), static_cast<float>(size.x),
                static_cast<float>(size.y));
}

void OrthoAtlas::render(const glm::vec3* directions, int n, const GpuScene& scene,
                        std::vector<glm::mat4>& lookups, std::vector<glm::ivec2>& origins) {
  if (n > tiles()) throw Error("", "orthographic shadow atlas", "more maps than tiles");
  const GladGLContext& api = *api_;
  lookups.resize(static_cast<std::size_t>(n));
  origins.resize(static_cast<std::size_t>(n));
  const int tiles = this->tiles();
  float* clips = block_data_.data();
  float* origin_data = clips + 16 * tiles;
  float* direction_data = origin_data + 4 * tiles;
  // Clip space as OrthoShadow's: x, y over the square of half width h, z = d.(p - c) / h.
  const float inv = 1.0f / half_width_;
  for (int i = 0; i < n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    const glm::ivec2 origin = glm::ivec2(i % grid_.x, i / grid_.x) * resolution_;
    const glm::mat4 clip = ortho_light_matrix(directions[i], centre_, inv, 0.0f, inv);
    // (u, v) over the tile in [0, 1], depth along d in world units.
    lookups[u] = ortho_light_matrix(directions[i], centre_, 0.5f * inv, 0.5f, 1.0f);
    origins[u] = origin;
    std::memcpy(clips + 16 * i, &clip[0][0], 16 * sizeof(float));
    origin_data[4 * i] = static_cast<float>(origin.x);
    origin_data[4 * i + 1] = static_cast<float>(origin.y);
    std::memcpy(direction_data + 4 * i, &directions[i][0], 3 * sizeof(float));
  }
  api.BindBuffer(GL_UNIFORM_BUFFER, block_.get());
  api.BufferData(GL_UNIFORM_BUFFER, static_cast<GLsizeiptr>(block_data_.size() * sizeof(float)),
                 block_data_.data(), GL_STREAM_DRAW);
  api.BindBufferBase(GL_UNIFORM_BUFFER, kOrthoBlockBinding, block_.get());
  current_ = 1 - current_;
  api.BindFramebuffer(GL_FRAMEBUFFER, fbo_[current_].get());
  const glm::ivec2 size = grid_ * resolution_;
  api.Viewport(0, 0, size.x, size.y);
  api.Disable(GL_SCISSOR_TEST);
  api.Enable(GL_DEPTH_TEST);
  api.DepthFunc(GL_LESS);
  api.DepthMask(GL_TRUE);
  api.Disable(GL_BLEND);
  api.ClearDepth(1.0); // far: nothing there, never shadowed
  api.Clear(GL_DEPTH_BUFFER_BIT);
  program_.use();
  scene.draw_covered(n, [&](const Material& m) { material_.bind_alpha(api, scene, m); });
}

} // namespace irad::gl
