#pragma once
// The scene's triangles and textures on the GPU: one interleaved vertex buffer (position, normal
// in 4 bytes (raster/scene/octahedral.h), and uv where the scene has texture coordinates: without,
// attribute 2 is off and reads GL's default (0, 0)), TEXCOORD_1, COLOR_0 and TANGENT in buffers of
// their own only when the scene has them (attributes kUv1Attribute, kColorAttribute and
// kTangentAttribute, raster/scene/material_glsl.h), one index buffer with the triangles grouped by
// material (each material's in chunks of 16-bit indices where its vertices allow:
// raster/scene/index_chunks.h), and the textures as linear RGBA32F with bilinear filtering (what
// the walk samples). Textures are uploaded only when the scene has them.
#include "core/scene/scene.h"
#include "raster/context/gl_objects.h"
#include "raster/scene/material_features.h"

#include <functional>
#include <vector>

namespace irad::gl {

// core/material/albedo_table.h's table as an RGB32F texture of AlbedoTable::kRough x kMu texels
// (texel (j, i): node (mu_i, r_j); raster/glsl/brdf_glsl.h brdf_albedo_glsl).
Texture albedo_table_texture(const GladGLContext& api);

class GpuScene {
public:
  GpuScene(const GladGLContext& api, const Scene& scene);

  // Re-uploads the positions and normals of the vertices the scene's animation moves (after
  // Animation::pose); nothing for a static scene.
  void update_vertices();

  // Draws every triangle, calling `bind(material)` before each material's range.
  void draw(const std::function<void(const Material&)>& bind) const;
  // A pass that needs no material but its coverage (depth, shadow, irradiance-only), every range
  // drawn `instances` times (gl_InstanceID 0..instances-1): every chunk in turn, binding nothing,
  // when the scene has no Mask or Blend material, else range by range with `bind_alpha` per
  // material (every camera pass then draws range by range, so gl_PrimitiveID, which the Blend hash
  // reads, is the same in all of them). vao: vertex_array() of the current context when that is not
  // the one this GpuScene was made in (nullptr: its own).
  void draw_covered(GLsizei instances, const std::function<void(const Material&)>& bind_alpha,
                    const VertexArray* vao = nullptr) const;
  // Draws only the ranges whose material satisfies `select` (`instances` times each); vao as
  // for draw_covered.
  void draw_if(const std::function<bool(const Material&)>& select,
               const std::function<void(const Material&)>& bind, GLsizei instances = 1,
               const VertexArray* vao = nullptr) const;
  // A vertex array over this scene's buffers made in the current context (vertex arrays are not
  // shared between contexts: raster/context/gl_thread.h), for draw_covered and draw_if there.
  VertexArray vertex_array() const { return vertex_array_with(indices_); }
  // A vertex array over this scene's vertex buffers, with the attributes of its own, and
  // `indices` as its element buffer: other index lists over the same vertices (the shadow
  // passes' clusters, raster/shadow/shadow_lod.h). Valid while this GpuScene lives.
  VertexArray vertex_array_with(const Buffer& indices) const;

  const Scene& scene() const { return *scene_; }
  // The bytes of its buffers and textures on the GPU.
  std::size_t bytes() const { return bytes_; }

  const MaterialFeatures& features() const { return features_; }

  // A chunk drawn once (a camera pass) of more than this many triangles is drawn in pieces of at
  // most this many, each followed by glFlush: llvmpipe holds what it binned of a draw until it
  // rasterizes it, so that the G-buffer of the 10M sphere box (256x256) held 75-111 MiB more
  // while it was drawn in chunks of up to 65,536 vertices, 18-23 MiB in pieces of 16,384
  // triangles (35-49 MiB in pieces of 65,536), in no more time and to the same bits. Every
  // camera pass draws the same pieces, so gl_PrimitiveID, which the Blend hash reads, stays the
  // same in all of them.
  static constexpr GLsizei kPieceTriangles = 16384;

  // albedo_table_texture, uploaded once; 0 unless the scene has a material that is not
  // Lambertian.
  GLuint albedo_table() const { return albedo_table_.get(); }

  // GL name of scene texture `index` (as in Scene::textures).
  GLuint texture(int index) const { return textures_[static_cast<std::size_t>(index)].get(); }

private:
  // One glDrawElementsBaseVertex: `count` indices of `type` from byte `offset`.
  struct Chunk {
    GLenum type;
    std::size_t offset;
    GLsizei count;
    GLint base_vertex;
  };
  // A material's triangles: chunks_[first_chunk, first_chunk + chunk_count).
  struct Range {
    std::uint32_t material;
    std::size_t first_chunk, chunk_count;
  };
  // ranges_, chunks_ and the bound element buffer's indices: the triangles grouped by material,
  // in the file's order within a material.
  void upload_grouped_indices(const Scene& scene);
  void draw_chunk(const Chunk& c, GLsizei instances) const;
  void draw_range(const Range& r, GLsizei instances = 1) const;
  // Every chunk, `instances` times, through `vao` (nullptr: the own one).
  void draw_everything(GLsizei instances, const VertexArray* vao) const;
  void bind_vertex_array(const VertexArray* vao) const {
    api_->BindVertexArray(vao ? vao->get() : vao_.get());
  }
  // The vertex attributes on the bound vertex array.
  void attach_attributes() const;

  const GladGLContext* api_;
  const Scene* scene_;
  VertexArray vao_;
  Buffer vertices_;
  Buffer indices_;
  Buffer uv1_;      // only with TEXCOORD_1
  Buffer colors_;   // only with COLOR_0
  Buffer tangents_; // only with normal maps (Scene::tangents)
  MaterialFeatures features_;
  std::vector<Range> ranges_;
  std::vector<Chunk> chunks_;
  std::vector<Texture> textures_;
  Texture albedo_table_;
  std::size_t bytes_ = 0;
};

} // namespace irad::gl
