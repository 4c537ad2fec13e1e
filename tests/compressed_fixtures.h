#pragma once
// Test helper: compressed geometry made with the libraries' own encoders (Draco for
// KHR_draco_mesh_compression, meshoptimizer for EXT_meshopt_compression), for the codec tests
// and for loader tests that build glTF files around the bytes.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace irad::test {

// An indexed triangle mesh: 3 floats per position and normal, 2 per texture coordinate, one
// element per vertex.
struct FixtureMesh {
  std::vector<float> positions;
  std::vector<float> normals;
  std::vector<float> uvs;
  std::vector<std::uint32_t> indices; // 3 per triangle
  std::size_t vertex_count() const { return positions.size() / 3; }
};

// The unit cube [-1, 1]^3: 24 vertices (4 per side, each with its side's normal and the uvs of
// the side's corners, in [0, 1]), 12 triangles wound counter-clockwise seen from outside.
FixtureMesh cube_mesh();

// A KHR_draco_mesh_compression bufferView's bytes and the attribute unique ids its
// "attributes" object maps POSITION, NORMAL and TEXCOORD_0 to.
struct DracoFixture {
  std::vector<unsigned char> bytes;
  int position_id = -1;
  int normal_id = -1;
  int texcoord_id = -1;
};

// Encodes `mesh` with draco::Encoder, every attribute quantized to `quantization_bits`.
DracoFixture draco_encode(const FixtureMesh& mesh, int quantization_bits = 14);

// EXT_meshopt_compression ATTRIBUTES bytes: `count` elements of `stride` bytes (a multiple of
// 4, at most 256).
std::vector<unsigned char> meshopt_encode_vertices(const void* elements, std::size_t count,
                                                   std::size_t stride);
// TRIANGLES bytes (meshopt_encodeIndexBuffer); indices.size() a multiple of 3.
std::vector<unsigned char> meshopt_encode_triangles(const std::vector<std::uint32_t>& indices,
                                                    std::size_t vertex_count);
// INDICES bytes (meshopt_encodeIndexSequence).
std::vector<unsigned char> meshopt_encode_sequence(const std::vector<std::uint32_t>& indices,
                                                   std::size_t vertex_count);

} // namespace irad::test
