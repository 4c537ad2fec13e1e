// Prints, as JSON, the compressed bytes that fuzz/make_seeds.py embeds (base64) in its seeds for
// the decoders Python cannot encode: a KHR_draco_mesh_compression cube, EXT_meshopt_compression
// streams (ATTRIBUTES, with the OCTAHEDRAL and EXPONENTIAL filters, and TRIANGLES) and a 2x2
// lossless WebP. Encoded by the libraries' own encoders (tests/compressed_fixtures.h, libwebp).
// Build and run (the output replaces SEED_BYTES in fuzz/make_seeds.py):
//   cmake --build build --target irad_seed_bytes && build/bin/irad_seed_bytes
#include "tests/compressed_fixtures.h"

#include <cmath>
#include <cstdio>
#include <draco/compression/decode.h>
#include <meshoptimizer.h>
#include <string>
#include <vector>
#include <webp/encode.h>

namespace {

std::string base64(const std::vector<unsigned char>& b) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < b.size(); i += 3) {
    const unsigned v = unsigned(b[i]) << 16 | (i + 1 < b.size() ? unsigned(b[i + 1]) << 8 : 0u) |
                       (i + 2 < b.size() ? unsigned(b[i + 2]) : 0u);
    out += k[v >> 18 & 63];
    out += k[v >> 12 & 63];
    out += i + 1 < b.size() ? k[v >> 6 & 63] : '=';
    out += i + 2 < b.size() ? k[v & 63] : '=';
  }
  return out;
}

} // namespace

int main() {
  using irad::test::FixtureMesh;
  const FixtureMesh cube = irad::test::cube_mesh();
  const std::size_t n = cube.vertex_count();

  // Draco: the cube, 11-bit quantization; the decoder tells the point and face counts.
  const irad::test::DracoFixture draco = irad::test::draco_encode(cube, 11);
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(draco.bytes.data()), draco.bytes.size());
  auto mesh = draco::Decoder().DecodeMeshFromBuffer(&buffer);
  if (!mesh.ok()) return 1;

  // meshopt: positions (float VEC3, stride 12, no filter), normals (OCTAHEDRAL, int8 x 4),
  // uvs (EXPONENTIAL, float VEC2 stride 8), indices (TRIANGLES, uint16).
  const auto positions =
      irad::test::meshopt_encode_vertices(cube.positions.data(), n, 3 * sizeof(float));
  std::vector<float> normals4;
  for (std::size_t i = 0; i < n; ++i)
    normals4.insert(normals4.end(),
                    {cube.normals[3 * i], cube.normals[3 * i + 1], cube.normals[3 * i + 2], 0.0f});
  std::vector<unsigned char> oct(n * 4);
  meshopt_encodeFilterOct(oct.data(), n, 4, 8, normals4.data());
  const auto normals = irad::test::meshopt_encode_vertices(oct.data(), n, 4);
  std::vector<unsigned char> exp(n * 8);
  meshopt_encodeFilterExp(exp.data(), n, 8, 12, cube.uvs.data());
  const auto uvs = irad::test::meshopt_encode_vertices(exp.data(), n, 8);
  const auto triangles = irad::test::meshopt_encode_triangles(cube.indices, n);
  std::vector<std::uint16_t> idx16(cube.indices.begin(), cube.indices.end());
  std::vector<unsigned char> tri16(meshopt_encodeIndexBufferBound(idx16.size(), n));
  tri16.resize(meshopt_encodeIndexBuffer(tri16.data(), tri16.size(), idx16.data(), idx16.size()));

  // WebP: 2x2 RGBA, lossless.
  const unsigned char rgba[16] = {255, 0, 0,   255, 0,   255, 0,   255,
                                  0,   0, 255, 255, 255, 255, 255, 128};
  std::uint8_t* webp_out = nullptr;
  const std::size_t webp_size = WebPEncodeLosslessRGBA(rgba, 2, 2, 8, &webp_out);
  const std::vector<unsigned char> webp(webp_out, webp_out + webp_size);
  WebPFree(webp_out);

  std::printf("{\n");
  std::printf("  \"draco\": {\"bytes\": \"%s\", \"points\": %u, \"faces\": %u, \"POSITION\": %d, "
              "\"NORMAL\": %d, \"TEXCOORD_0\": %d},\n",
              base64(draco.bytes).c_str(), unsigned(mesh.value()->num_points()),
              unsigned(mesh.value()->num_faces()), draco.position_id, draco.normal_id,
              draco.texcoord_id);
  std::printf("  \"meshopt\": {\"count\": %zu, \"triangles\": %zu, \"positions\": \"%s\", "
              "\"normals_oct8\": \"%s\", \"uvs_exp\": \"%s\", \"indices_u16\": \"%s\"},\n",
              n, cube.indices.size(), base64(positions).c_str(), base64(normals).c_str(),
              base64(uvs).c_str(), base64(tri16).c_str());
  (void)triangles;
  std::printf("  \"webp\": \"%s\"\n}\n", base64(webp).c_str());
  return 0;
}
