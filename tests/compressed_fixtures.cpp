#include "compressed_fixtures.h"

#include <array>
#include <stdexcept>

#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <meshoptimizer.h>

namespace irad::test {

FixtureMesh cube_mesh() {
  FixtureMesh mesh;
  // Each side: its axis, the outward sign, and two tangent axes (u, v) with u x v = normal.
  struct Side {
    int axis, u, v;
    float sign;
  };
  constexpr std::array<Side, 6> sides{{{0, 1, 2, 1.0f},
                                       {0, 2, 1, -1.0f},
                                       {1, 2, 0, 1.0f},
                                       {1, 0, 2, -1.0f},
                                       {2, 0, 1, 1.0f},
                                       {2, 1, 0, -1.0f}}};
  constexpr std::array<std::array<float, 2>, 4> corners{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  for (const Side& side : sides) {
    const auto first = std::uint32_t(mesh.vertex_count());
    for (const auto& corner : corners) {
      std::array<float, 3> p{}, n{};
      p[std::size_t(side.axis)] = side.sign;
      p[std::size_t(side.u)] = 2.0f * corner[0] - 1.0f;
      p[std::size_t(side.v)] = 2.0f * corner[1] - 1.0f;
      n[std::size_t(side.axis)] = side.sign;
      mesh.positions.insert(mesh.positions.end(), p.begin(), p.end());
      mesh.normals.insert(mesh.normals.end(), n.begin(), n.end());
      mesh.uvs.insert(mesh.uvs.end(), corner.begin(), corner.end());
    }
    for (const std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(first + i);
  }
  return mesh;
}

namespace {

// Adds one attribute of `components` floats per vertex, set on every face's corners.
int add_attribute(draco::TriangleSoupMeshBuilder& builder, draco::GeometryAttribute::Type type,
                  int components, const std::vector<float>& values,
                  const std::vector<std::uint32_t>& indices) {
  const int id =
      builder.AddAttribute(type, static_cast<std::int8_t>(components), draco::DT_FLOAT32);
  const auto at = [&](std::uint32_t vertex) {
    return values.data() + std::size_t(vertex) * std::size_t(components);
  };
  for (std::size_t f = 0; f < indices.size() / 3; ++f) {
    builder.SetAttributeValuesForFace(id, draco::FaceIndex(std::uint32_t(f)), at(indices[3 * f]),
                                      at(indices[3 * f + 1]), at(indices[3 * f + 2]));
  }
  return id;
}

} // namespace

DracoFixture draco_encode(const FixtureMesh& mesh, int quantization_bits) {
  draco::TriangleSoupMeshBuilder builder;
  builder.Start(int(mesh.indices.size() / 3));
  const int position =
      add_attribute(builder, draco::GeometryAttribute::POSITION, 3, mesh.positions, mesh.indices);
  const int normal =
      add_attribute(builder, draco::GeometryAttribute::NORMAL, 3, mesh.normals, mesh.indices);
  const int texcoord =
      add_attribute(builder, draco::GeometryAttribute::TEX_COORD, 2, mesh.uvs, mesh.indices);
  const std::unique_ptr<draco::Mesh> built = builder.Finalize();
  if (!built) throw std::runtime_error("draco_encode: the mesh does not build");

  draco::Encoder encoder;
  for (const auto type : {draco::GeometryAttribute::POSITION, draco::GeometryAttribute::NORMAL,
                          draco::GeometryAttribute::TEX_COORD}) {
    encoder.SetAttributeQuantization(type, quantization_bits);
  }
  draco::EncoderBuffer buffer;
  if (!encoder.EncodeMeshToBuffer(*built, &buffer).ok()) {
    throw std::runtime_error("draco_encode: the mesh does not encode");
  }
  DracoFixture fixture;
  const auto* data = reinterpret_cast<const unsigned char*>(buffer.data());
  fixture.bytes.assign(data, data + buffer.size());
  fixture.position_id = int(built->attribute(position)->unique_id());
  fixture.normal_id = int(built->attribute(normal)->unique_id());
  fixture.texcoord_id = int(built->attribute(texcoord)->unique_id());
  return fixture;
}

std::vector<unsigned char> meshopt_encode_vertices(const void* elements, std::size_t count,
                                                   std::size_t stride) {
  std::vector<unsigned char> out(meshopt_encodeVertexBufferBound(count, stride));
  out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), elements, count, stride));
  return out;
}

std::vector<unsigned char> meshopt_encode_triangles(const std::vector<std::uint32_t>& indices,
                                                    std::size_t vertex_count) {
  std::vector<unsigned char> out(meshopt_encodeIndexBufferBound(indices.size(), vertex_count));
  out.resize(meshopt_encodeIndexBuffer(out.data(), out.size(), indices.data(), indices.size()));
  return out;
}

std::vector<unsigned char> meshopt_encode_sequence(const std::vector<std::uint32_t>& indices,
                                                   std::size_t vertex_count) {
  std::vector<unsigned char> out(meshopt_encodeIndexSequenceBound(indices.size(), vertex_count));
  out.resize(meshopt_encodeIndexSequence(out.data(), out.size(), indices.data(), indices.size()));
  return out;
}

} // namespace irad::test
