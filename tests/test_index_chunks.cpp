// The scene's indices in chunks of 16-bit indices (raster/scene/index_chunks.h): every triangle in
// exactly one chunk, in order; a narrow chunk's vertices within 16 bits of its base; a grid in
// vertex order all narrow; scattered vertices in one wide chunk. On the GPU
// (raster/scene/gpu_scene.h) the G-buffer of a height field is the same to the bit whichever way
// its vertices are numbered (narrow chunks at other bases, wide chunks) and however its
// materials split its triangles into runs, and a chunk drawn in pieces covers all of it.
#include "raster/context/gl_context.h"
#include "raster/scene/index_chunks.h"
#include "tests/height_field.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <numeric>
#include <random>

namespace irad {
namespace IRAD_UNITY_ID {

using namespace test_support;
using gl::IndexChunk;

using Parts = std::vector<std::span<const glm::uvec3>>;

// The chunks cover [0, n) once, in order, and each narrow one's vertices lie in
// [base, base + 65535], base its smallest; returns the triangles in narrow chunks.
std::size_t check_chunks(const std::vector<IndexChunk>& chunks,
                         const std::vector<glm::uvec3>& triangles) {
  std::size_t next = 0, narrow = 0;
  for (const IndexChunk& c : chunks) {
    EXPECT_EQ(c.first, next);
    EXPECT_GT(c.count, 0u);
    next = c.first + c.count;
    if (!c.narrow) {
      EXPECT_EQ(c.base, 0u);
      continue;
    }
    narrow += c.count;
    std::uint32_t lo = ~0u;
    for (std::size_t t = c.first; t < c.first + c.count; ++t)
      for (int i = 0; i < 3; ++i) {
        EXPECT_GE(triangles[t][i], c.base);
        EXPECT_LE(triangles[t][i] - c.base, gl::kNarrowSpan);
        lo = std::min(lo, triangles[t][i]);
      }
    EXPECT_EQ(c.base, lo);
  }
  EXPECT_EQ(next, triangles.size());
  return narrow;
}

std::vector<IndexChunk> chunks_of(const std::vector<glm::uvec3>& triangles) {
  const Parts parts{triangles};
  return gl::index_chunks(parts);
}

TEST(IndexChunks, AGridInVertexOrderIsNarrow) {
  Scene s;
  add_terrain(s, 300, 0); // 301^2 = 90,601 vertices, 180,000 triangles
  const std::vector<IndexChunk> chunks = chunks_of(s.triangles);
  EXPECT_EQ(check_chunks(chunks, s.triangles), s.triangles.size());
  // Quads reach 65,535 within row 216 (rows of 301 vertices); the rest fits in a second chunk.
  EXPECT_EQ(chunks.size(), 2u);
}

TEST(IndexChunks, AListWithinSixteenBitsIsOneNarrowChunk) {
  std::vector<glm::uvec3> triangles;
  for (std::uint32_t t = 0; t < 12; ++t)
    triangles.emplace_back(100000 + t, 100001 + t, 100000 + 65535 - t);
  const std::vector<IndexChunk> chunks = chunks_of(triangles);
  ASSERT_EQ(chunks.size(), 1u);
  EXPECT_TRUE(chunks[0].narrow);
  EXPECT_EQ(chunks[0].base, 100000u);
  check_chunks(chunks, triangles);
  EXPECT_EQ(gl::chunk_bytes(chunks[0]), 72u); // 36 indices of 2 bytes
}

TEST(IndexChunks, ScatteredVerticesAreOneWideChunk) {
  std::mt19937 random(7);
  std::uniform_int_distribution<std::uint32_t> vertex(0, 999999);
  std::vector<glm::uvec3> triangles(20000);
  for (glm::uvec3& t : triangles) t = {vertex(random), vertex(random), vertex(random)};
  const std::vector<IndexChunk> chunks = chunks_of(triangles);
  ASSERT_EQ(chunks.size(), 1u);
  EXPECT_FALSE(chunks[0].narrow);
  check_chunks(chunks, triangles);
  EXPECT_EQ(gl::chunk_bytes(chunks[0]), 240000u);
}

TEST(IndexChunks, ATriangleWiderThanSixteenBitsSplitsAGrid) {
  Scene s;
  add_terrain(s, 100, 0);
  std::vector<glm::uvec3> triangles = s.triangles;
  triangles.insert(triangles.begin() + 10000, glm::uvec3(0, 5, 200000));
  const std::vector<IndexChunk> chunks = chunks_of(triangles);
  // The grid's first 10,000 triangles, the wide one alone, the rest of the grid.
  ASSERT_EQ(chunks.size(), 3u);
  EXPECT_TRUE(chunks[0].narrow);
  EXPECT_FALSE(chunks[1].narrow);
  EXPECT_EQ(chunks[1].first, 10000u);
  EXPECT_EQ(chunks[1].count, 1u);
  EXPECT_TRUE(chunks[2].narrow);
  EXPECT_EQ(check_chunks(chunks, triangles), s.triangles.size());
}

TEST(IndexChunks, ShortNarrowRunsMergeIntoWideChunks) {
  // Runs of 100 triangles, each in a window of its own, far apart: each would be a narrow
  // chunk of 100 triangles; all together they are one wide chunk.
  std::vector<glm::uvec3> triangles;
  for (std::uint32_t run = 0; run < 50; ++run)
    for (std::uint32_t t = 0; t < 100; ++t)
      triangles.emplace_back(run * 100000 + t, run * 100000 + t + 1, run * 100000 + t + 2);
  const std::vector<IndexChunk> chunks = chunks_of(triangles);
  ASSERT_EQ(chunks.size(), 1u);
  EXPECT_FALSE(chunks[0].narrow);
  check_chunks(chunks, triangles);
}

TEST(IndexChunks, PartsChunkAsOneList) {
  Scene s;
  add_terrain(s, 300, 0);
  const std::span<const glm::uvec3> all(s.triangles);
  const Parts parts{all.subspan(0, 7), all.subspan(7, 90000), all.subspan(90007)};
  const std::vector<IndexChunk> whole = chunks_of(s.triangles), split = gl::index_chunks(parts);
  ASSERT_EQ(split.size(), whole.size());
  for (std::size_t k = 0; k < whole.size(); ++k) {
    EXPECT_EQ(split[k].first, whole[k].first);
    EXPECT_EQ(split[k].count, whole[k].count);
    EXPECT_EQ(split[k].base, whole[k].base);
  }
  std::vector<glm::uvec3> walked;
  gl::for_each_triangle(parts, 5, 90004, [&](const glm::uvec3& t) { walked.push_back(t); });
  ASSERT_EQ(walked.size(), 90004u);
  EXPECT_TRUE(std::equal(walked.begin(), walked.end(), s.triangles.begin() + 5));
}

// `s` with its vertices renumbered by `order` (new vertex i is old vertex order[i]).
Scene renumbered(const Scene& s, const std::vector<std::uint32_t>& order) {
  Scene out = s;
  std::vector<std::uint32_t> new_index(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    out.positions[i] = s.positions[order[i]];
    out.normals[i] = s.normals[order[i]];
    new_index[order[i]] = static_cast<std::uint32_t>(i);
  }
  for (glm::uvec3& t : out.triangles) t = {new_index[t.x], new_index[t.y], new_index[t.z]};
  return out;
}

TEST(IndexChunks, TheGBufferIsTheSameWhicheverChunksDrawIt) {
  const Scene s = lit_terrain(300); // narrow chunks: two over the terrain, one over the light
  const View view = make_view(s.cameras[0], s.bounds, 96, 72);
  std::vector<std::uint32_t> reversed(s.positions.size()), shuffled(s.positions.size());
  std::iota(reversed.rbegin(), reversed.rend(), 0u); // narrow chunks at other bases
  std::iota(shuffled.begin(), shuffled.end(), 0u);
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(3)); // wide chunks
  Scene striped = s; // every other row of quads in a second material: 300 runs per material
  const std::uint32_t second = add_material(striped, glm::vec3(0.6f));
  for (std::size_t t = 0; t < 180000; ++t)
    if ((t / 600) % 2 == 1) striped.triangle_material[t] = second;
  const Scene variants[3] = {renumbered(s, reversed), renumbered(s, shuffled), striped};

  const auto context = gl::create_osmesa_context();
  const gl::CurrentScope current(*context);
  const GladGLContext& api = context->api();
  const gl::GpuScene gpu(api, s);
  const GBufferPixels expected = draw_gbuffer(api, gpu, view, nullptr);
  std::size_t covered = 0;
  for (const glm::vec4& p : expected.position) covered += p.w != 0.0f;
  EXPECT_GT(covered, expected.position.size() / 2);
  // 90,605 vertices of 16 bytes (no uvs), 180,002 triangles of 2-byte indices, each of the three
  // chunks (two over the terrain, one over the light) padded to 4 bytes.
  const std::size_t least = 90605 * 16 + 180002 * 6;
  EXPECT_GE(gpu.bytes(), least);
  EXPECT_LE(gpu.bytes(), least + 3 * 2);
  for (const Scene& v : variants) {
    const gl::GpuScene other(api, v);
    const GBufferPixels got = draw_gbuffer(api, other, view, nullptr);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < got.position.size(); ++i)
      differ += got.position[i] != expected.position[i] || got.normal[i] != expected.normal[i];
    EXPECT_EQ(differ, 0u);
  }
}

// A chunk of more than GpuScene::kPieceTriangles is drawn in pieces: every piece, from 2-byte
// (vertices in grid order: two narrow chunks) and from 4-byte (90,601 vertices shuffled: one
// wide chunk) indices, lands where it should. The terrain fills the whole frame seen from
// above, so a piece left out or drawn from the wrong offset leaves pixels empty or on the wrong
// height (2-byte offsets for the wide chunk: 1792 of 4096 pixels empty).
TEST(IndexChunks, PiecesOfALargeChunkCoverItAll) {
  Scene s;
  add_terrain(s, 300, add_material(s, glm::vec3(0.6f))); // 180,000 triangles: 11 pieces
  s.cameras.push_back(look_at({0.0f, 3.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0, 0, -1}, 0.45f));
  finish(s);
  ASSERT_GT(s.triangles.size(), 4u * gl::GpuScene::kPieceTriangles);
  const View view = make_view(s.cameras[0], s.bounds, 64, 64);
  std::vector<std::uint32_t> shuffled(s.positions.size());
  std::iota(shuffled.begin(), shuffled.end(), 0u);
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(5));

  const auto context = gl::create_osmesa_context();
  const gl::CurrentScope current(*context);
  const GladGLContext& api = context->api();
  for (const Scene& v : {s, renumbered(s, shuffled)}) {
    const gl::GpuScene gpu(api, v);
    const GBufferPixels got = draw_gbuffer(api, gpu, view, nullptr);
    std::size_t empty = 0, off = 0;
    for (const glm::vec4& p : got.position) {
      empty += p.w == 0.0f;
      // The flat triangles lie within 1e-3 of the bumps (their largest sag across a quad of
      // 2 / 300: 0.01 x (41 x 2 / 300)^2 / 8 = 9.3e-5, and the two coarser octaves' less).
      float y = 0.0f;
      for (const auto& o : {glm::vec3(2.1f, 1.7f, 0.12f), glm::vec3(5.3f, 6.1f, 0.04f),
                            glm::vec3(41.0f, 37.0f, 0.01f)})
        y += o.z * std::sin(o.x * p.x) * std::cos(o.y * p.z);
      off += p.w != 0.0f && std::abs(p.y - y) > 1e-3f;
    }
    EXPECT_EQ(empty, 0u);
    EXPECT_EQ(off, 0u);
  }
}

} // namespace IRAD_UNITY_ID
} // namespace irad
