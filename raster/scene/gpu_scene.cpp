#include "raster/scene/gpu_scene.h"

#include "core/animation/animation.h"
#include "core/material/albedo_table.h"
#include "core/util/error.h"
#include "core/util/parallel_rows.h"
#include "raster/scene/index_chunks.h"
#include "raster/scene/octahedral.h"

#include <cstddef>
#include <cstring>
#include <span>

namespace irad::gl {

namespace {

GLint gl_wrap(Wrap w) {
  switch (w) {
  case Wrap::ClampToEdge:
    return GL_CLAMP_TO_EDGE;
  case Wrap::MirroredRepeat:
    return GL_MIRRORED_REPEAT;
  case Wrap::Repeat:
    break;
  }
  return GL_REPEAT;
}

Texture upload_texture(const GladGLContext& api, const irad::Texture& t) {
  Texture tex = make_texture(api);
  api.BindTexture(GL_TEXTURE_2D, tex.get());
  // Row 0 of Texture is v = 0; GL's first row is t = 0, so uv maps to texture() unchanged.
  api.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, t.width, t.height, 0, GL_RGBA, GL_FLOAT,
                 t.texels.data());
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, gl_wrap(t.wrap_s));
  api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, gl_wrap(t.wrap_t));
  return tex;
}

// The interleaved vertex: position (3 floats), normal (octahedral, 2 x int16:
// raster/scene/octahedral.h), and the uv (2 floats) where the scene has texture coordinates (else
// attribute 2 stays off and reads GL's default (0, 0)): 16 or 24 bytes a vertex.
constexpr std::size_t kNormalOffset = 12, kUvOffset = 16;
std::size_t vertex_bytes(const Scene& scene) {
  return scene.uvs.empty() ? kUvOffset : kUvOffset + 8;
}

// Writes vertex i of the scene at `out` (vertex_bytes(scene) bytes).
void write_vertex(const Scene& scene, std::size_t i, std::byte* out) {
  std::memcpy(out, &scene.positions[i], 12);
  const glm::i16vec2 normal = octahedral_encode(scene.normals[i]);
  std::memcpy(out + kNormalOffset, &normal, 4);
  if (!scene.uvs.empty()) std::memcpy(out + kUvOffset, &scene.uvs[i], 8);
}

// A tightly packed float attribute array (vec2 or vec4 per vertex).
template <class V>
Buffer upload_attribute(const GladGLContext& api, const std::vector<V>& values) {
  Buffer buffer = make_buffer(api);
  api.BindBuffer(GL_ARRAY_BUFFER, buffer.get());
  api.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(values.size() * sizeof(V)), values.data(),
                 GL_STATIC_DRAW);
  return buffer;
}

// `buffer` (tightly packed, `components` floats per vertex) as attribute `location` of the bound
// vertex array.
void attach_packed(const GladGLContext& api, const Buffer& buffer, GLuint location,
                   GLint components) {
  api.BindBuffer(GL_ARRAY_BUFFER, buffer.get());
  api.EnableVertexAttribArray(location);
  api.VertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, 0, nullptr);
}

// One material's triangles: the runs of consecutive triangles of the scene that it holds, in
// the file's order.
struct MaterialRuns {
  std::uint32_t material;
  std::vector<std::span<const glm::uvec3>> runs;
};

// The materials that hold triangles, ascending, each with its runs (a run per primitive in a
// file's usual order; one per triangle, 16 bytes each, where materials alternate triangle by
// triangle).
std::vector<MaterialRuns> material_runs(const Scene& scene) {
  std::vector<std::vector<std::span<const glm::uvec3>>> by_material;
  const std::span<const glm::uvec3> all(scene.triangles);
  for (std::size_t t = 0; t < scene.triangle_count();) {
    const std::uint32_t m = scene.triangle_material[t];
    std::size_t end = t + 1;
    while (end < scene.triangle_count() && scene.triangle_material[end] == m) ++end;
    if (m >= by_material.size()) by_material.resize(m + 1);
    by_material[m].push_back(all.subspan(t, end - t));
    t = end;
  }
  std::vector<MaterialRuns> out;
  for (std::size_t m = 0; m < by_material.size(); ++m)
    if (!by_material[m].empty())
      out.push_back({static_cast<std::uint32_t>(m), std::move(by_material[m])});
  return out;
}

// Chunk c's indices at `out` (2 bytes an index, less its base, when narrow; else 4).
void write_chunk(std::span<const std::span<const glm::uvec3>> runs, const IndexChunk& c,
                 std::byte* out) {
  if (c.narrow) {
    auto* to = reinterpret_cast<std::uint16_t*>(out);
    for_each_triangle(runs, c.first, c.count, [&](const glm::uvec3& v) {
      for (int i = 0; i < 3; ++i) *to++ = static_cast<std::uint16_t>(v[i] - c.base);
    });
  } else {
    auto* to = reinterpret_cast<glm::uvec3*>(out);
    for_each_triangle(runs, c.first, c.count, [&](const glm::uvec3& v) { *to++ = v; });
  }
}

} // namespace

Texture albedo_table_texture(const GladGLContext& api) {
  static_assert(sizeof(AlbedoTable::Terms) == 3 * sizeof(float));
  Texture tex = make_float_texture(api, AlbedoTable::kRough, AlbedoTable::kMu, GL_RGB32F, GL_RGB);
  api.BindTexture(GL_TEXTURE_2D, tex.get());
  api.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  api.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, AlbedoTable::kRough, AlbedoTable::kMu, GL_RGB, GL_FLOAT,
                    AlbedoTable::get().cells().data());
  api.BindTexture(GL_TEXTURE_2D, 0);
  return tex;
}

void GpuScene::update_vertices() {
  if (!scene_->animation) return;
  api_->BindBuffer(GL_ARRAY_BUFFER, vertices_.get());
  const std::size_t bytes = vertex_bytes(*scene_);
  std::vector<std::byte> run;
  // The moving vertices (ascending) form contiguous runs of the scene's arrays: one upload per
  // run.
  const std::vector<std::uint32_t> moving = scene_->animation->moving_vertices();
  for (std::size_t k = 0; k < moving.size();) {
    const std::uint32_t first = moving[k];
    std::size_t count = 0;
    run.clear();
    while (k < moving.size() && moving[k] == first + count) {
      run.resize((count + 1) * bytes);
      write_vertex(*scene_, moving[k++], &run[count++ * bytes]);
    }
    api_->BufferSubData(GL_ARRAY_BUFFER, GLintptr(first * bytes), GLsizeiptr(run.size()),
                        run.data());
  }
}

GpuScene::GpuScene(const GladGLContext& api, const Scene& scene)
    : api_(&api), scene_(&scene), vao_(make_vertex_array(api)), vertices_(make_buffer(api)),
      indices_(make_buffer(api)), features_(MaterialFeatures::of(scene)) {
  api.BindBuffer(GL_ARRAY_BUFFER, vertices_.get());
  const std::size_t bytes = vertex_bytes(scene);
  bytes_ = scene.positions.size() * bytes;
  fill_buffer(
      api, GL_ARRAY_BUFFER, scene.positions.size() * bytes,
      scene.animation ? GL_DYNAMIC_DRAW : GL_STATIC_DRAW,
      [&](void* storage) {
        auto* out = static_cast<std::byte*>(storage);
        parallel_chunks(scene.positions.size(), [&](std::size_t first, std::size_t end) {
          for (std::size_t i = first; i < end; ++i) write_vertex(scene, i, out + i * bytes);
        });
      },
      "gpu scene");
  // The optional arrays run parallel to the positions (core/scene/scene.h): GL must never read past
  // one.
  if ((features_.uv1 && scene.uvs1.size() != scene.positions.size()) ||
      (features_.colors && scene.colors.size() != scene.positions.size()) ||
      (features_.normal_maps && scene.tangents.size() != scene.positions.size()))
    throw Error(scene.source, "gpu scene", "TEXCOORD_1, COLOR_0 or TANGENT not one per vertex");
  if (features_.uv1) uv1_ = upload_attribute(api, scene.uvs1);
  if (features_.colors) colors_ = upload_attribute(api, scene.colors);
  if (features_.normal_maps) tangents_ = upload_attribute(api, scene.tangents);
  bytes_ += scene.positions.size() * ((features_.uv1 ? 8 : 0) + (features_.colors ? 16 : 0) +
                                      (features_.normal_maps ? 16 : 0));

  api.BindVertexArray(vao_.get());
  api.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.get());
  upload_grouped_indices(scene);
  attach_attributes();

  for (const irad::Texture& t : scene.textures) {
    textures_.push_back(upload_texture(api, t));
    bytes_ += std::size_t(t.width) * std::size_t(t.height) * 16; // RGBA32F
  }
  if (features_.glossy) {
    albedo_table_ = albedo_table_texture(api);
    bytes_ += std::size_t(AlbedoTable::kRough) * AlbedoTable::kMu * sizeof(AlbedoTable::Terms);
  }
}

void GpuScene::upload_grouped_indices(const Scene& scene) {
  const std::vector<MaterialRuns> materials = material_runs(scene);
  std::vector<std::vector<IndexChunk>> chunks(materials.size());
  std::size_t bytes = 0;
  for (std::size_t i = 0; i < materials.size(); ++i) {
    chunks[i] = index_chunks(materials[i].runs);
    ranges_.push_back({materials[i].material, chunks_.size(), chunks[i].size()});
    for (const IndexChunk& c : chunks[i]) {
      chunks_.push_back({c.narrow ? GLenum(GL_UNSIGNED_SHORT) : GLenum(GL_UNSIGNED_INT), bytes,
                         static_cast<GLsizei>(3 * c.count), static_cast<GLint>(c.base)});
      bytes += chunk_bytes(c);
    }
  }
  bytes_ += bytes;
  fill_buffer(
      *api_, GL_ELEMENT_ARRAY_BUFFER, bytes, GL_STATIC_DRAW,
      [&](void* storage) {
        auto* out = static_cast<std::byte*>(storage);
        std::size_t k = 0;
        for (std::size_t i = 0; i < materials.size(); ++i)
          for (const IndexChunk& c : chunks[i])
            write_chunk(materials[i].runs, c, out + chunks_[k++].offset);
      },
      "gpu scene");
}

void GpuScene::attach_attributes() const {
  const GladGLContext& api = *api_;
  api.BindBuffer(GL_ARRAY_BUFFER, vertices_.get());
  const std::size_t bytes = vertex_bytes(*scene_);
  const auto stride = static_cast<GLsizei>(bytes);
  const auto at = [](std::size_t offset) { return reinterpret_cast<const void*>(offset); };
  api.EnableVertexAttribArray(0);
  api.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, at(0));
  // Integers, not GL's normalized shorts (whose conversion GL 3.3 defines otherwise than 4.2):
  // the shader divides by kOctahedralScale.
  api.EnableVertexAttribArray(1);
  api.VertexAttribIPointer(1, 2, GL_SHORT, stride, at(kNormalOffset));
  if (bytes > kUvOffset) {
    api.EnableVertexAttribArray(2);
    api.VertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, stride, at(kUvOffset));
  }
  if (uv1_) attach_packed(api, uv1_, kUv1Attribute, 2);
  if (colors_) attach_packed(api, colors_, kColorAttribute, 4);
  if (tangents_) attach_packed(api, tangents_, kTangentAttribute, 4);
}

VertexArray GpuScene::vertex_array_with(const Buffer& indices) const {
  VertexArray vao = make_vertex_array(*api_);
  api_->BindVertexArray(vao.get());
  api_->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices.get());
  attach_attributes();
  api_->BindVertexArray(0);
  return vao;
}

void GpuScene::draw_covered(GLsizei instances,
                            const std::function<void(const Material&)>& bind_alpha,
                            const VertexArray* vao) const {
  if (!features_.alpha) {
    draw_everything(instances, vao);
    return;
  }
  draw_if([](const Material&) { return true; }, bind_alpha, instances, vao);
}

void GpuScene::draw_chunk(const Chunk& c, GLsizei instances) const {
  if (instances > 1) {
    api_->DrawElementsInstancedBaseVertex(GL_TRIANGLES, c.count, c.type,
                                          reinterpret_cast<const void*>(c.offset), instances,
                                          c.base_vertex);
    return;
  }
  constexpr GLsizei kPieceIndices = 3 * kPieceTriangles;
  if (c.count <= kPieceIndices) {
    api_->DrawElementsBaseVertex(GL_TRIANGLES, c.count, c.type,
                                 reinterpret_cast<const void*>(c.offset), c.base_vertex);
    return;
  }
  const std::size_t index_bytes = c.type == GL_UNSIGNED_SHORT ? 2 : 4;
  for (GLsizei k = 0; k < c.count; k += kPieceIndices) {
    const auto offset = c.offset + index_bytes * static_cast<std::size_t>(k);
    api_->DrawElementsBaseVertex(GL_TRIANGLES, std::min(kPieceIndices, c.count - k), c.type,
                                 reinterpret_cast<const void*>(offset), c.base_vertex);
    api_->Flush();
  }
}

void GpuScene::draw_range(const Range& r, GLsizei instances) const {
  for (std::size_t k = r.first_chunk; k < r.first_chunk + r.chunk_count; ++k)
    draw_chunk(chunks_[k], instances);
}

void GpuScene::draw_everything(GLsizei instances, const VertexArray* vao) const {
  bind_vertex_array(vao);
  for (const Chunk& c : chunks_) draw_chunk(c, instances);
}

void GpuScene::draw(const std::function<void(const Material&)>& bind) const {
  draw_if([](const Material&) { return true; }, bind);
}

void GpuScene::draw_if(const std::function<bool(const Material&)>& select,
                       const std::function<void(const Material&)>& bind, GLsizei instances,
                       const VertexArray* vao) const {
  bind_vertex_array(vao);
  for (const Range& r : ranges_) {
    const Material& m = scene_->materials[r.material];
    if (!select(m)) continue;
    bind(m);
    draw_range(r, instances);
  }
}

} // namespace irad::gl
