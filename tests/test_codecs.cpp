// core/gltf/decode/codecs.h and core/gltf/decode/image_decode.h: round trips through the libraries'
// own encoders, corrupt data, limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <utility>

#include <meshoptimizer.h>
#include <stb_image_write.h>
#include <webp/encode.h>

#include "compressed_fixtures.h"
#include "core/gltf/decode/codecs.h"
#include "core/gltf/decode/image_decode.h"

namespace IRAD_UNITY_ID {

using irad::gltf::CodecError;
using irad::gltf::decode_image;
using irad::gltf::decode_meshopt;
using irad::gltf::DecodedImage;
using irad::gltf::DracoMesh;
using irad::gltf::ImageError;
using irad::gltf::ImageFormat;
using irad::gltf::ImageLimits;
using Bytes = std::vector<unsigned char>;

template <typename T>
std::vector<T> as(const Bytes& bytes) {
  std::vector<T> out(bytes.size() / sizeof(T));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
  return out;
}

template <typename T>
Bytes bytes_of(const std::vector<T>& values) {
  Bytes out(values.size() * sizeof(T));
  std::memcpy(out.data(), values.data(), out.size());
  return out;
}

Bytes random_bytes(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  Bytes out(n);
  for (auto& b : out) b = static_cast<unsigned char>(rng() & 0xFF);
  return out;
}

// Unit vectors spread over the sphere (a Fibonacci spiral), 4 floats each (w = 0).
std::vector<float> unit_vectors(std::size_t count) {
  std::vector<float> out;
  for (std::size_t i = 0; i < count; ++i) {
    const double z = 1.0 - 2.0 * (double(i) + 0.5) / double(count);
    const double r = std::sqrt(1.0 - z * z), phi = 2.39996322972865332 * double(i);
    out.insert(out.end(), {float(r * std::cos(phi)), float(r * std::sin(phi)), float(z), 0.0f});
  }
  return out;
}

// --- EXT_meshopt_compression ---

TEST(MeshoptCodec, AttributesRoundTripExactly) {
  constexpr std::size_t count = 100, stride = 16;
  std::vector<float> vertices(count * stride / 4);
  for (std::size_t i = 0; i < vertices.size(); ++i) vertices[i] = float(i % 7) * 0.25f - float(i);
  const Bytes encoded = irad::test::meshopt_encode_vertices(vertices.data(), count, stride);
  EXPECT_EQ(as<float>(decode_meshopt(encoded.data(), encoded.size(), count, stride, "ATTRIBUTES",
                                     "NONE")),
            vertices);
}

TEST(MeshoptCodec, TrianglesAndIndicesRoundTripExactlyAt2And4Bytes) {
  const irad::test::FixtureMesh cube = irad::test::cube_mesh();
  const std::size_t n = cube.indices.size();
  const Bytes triangles = irad::test::meshopt_encode_triangles(cube.indices, cube.vertex_count());
  const Bytes sequence = irad::test::meshopt_encode_sequence(cube.indices, cube.vertex_count());
  const std::vector<std::uint16_t> short_indices(cube.indices.begin(), cube.indices.end());
  using Case = std::pair<const char*, const Bytes*>;
  for (const auto& [mode, bytes] : {Case{"TRIANGLES", &triangles}, Case{"INDICES", &sequence}}) {
    EXPECT_EQ(as<std::uint32_t>(decode_meshopt(bytes->data(), bytes->size(), n, 4, mode, "NONE")),
              cube.indices)
        << mode;
    EXPECT_EQ(as<std::uint16_t>(decode_meshopt(bytes->data(), bytes->size(), n, 2, mode, "NONE")),
              short_indices)
        << mode;
  }
}

// Encodes `data` (4 floats per element) with a meshopt encode filter, then the vertex codec;
// returns the decoded, unfiltered elements.
template <typename Encode>
Bytes filtered_round_trip(Encode encode, const std::vector<float>& data, std::size_t stride,
                          int bits, const char* filter) {
  const std::size_t count = data.size() / 4;
  Bytes filtered(count * stride);
  encode(filtered.data(), count, stride, bits, data.data());
  const Bytes encoded = irad::test::meshopt_encode_vertices(filtered.data(), count, stride);
  return decode_meshopt(encoded.data(), encoded.size(), count, stride, "ATTRIBUTES", filter);
}

// The largest difference between `expected` (4 per element, the first `compare` compared) and
// the decoded normalized integers.
template <typename T>
double max_error(const std::vector<float>& expected, const Bytes& decoded, int compare) {
  const std::vector<T> values = as<T>(decoded);
  double worst = 0.0;
  for (std::size_t e = 0; e < expected.size() / 4; ++e) {
    for (std::size_t c = 0; c < std::size_t(compare); ++c) {
      const double v = double(values[4 * e + c]) / double(std::numeric_limits<T>::max());
      worst = std::max(worst, std::abs(v - double(expected[4 * e + c])));
    }
  }
  return worst;
}

TEST(MeshoptCodec, OctahedralFilterWithinItsPrecision) {
  const std::vector<float> normals = unit_vectors(200);
  // 16-bit components, 16-bit octahedral encoding (stride 8): the error is a few 2^-15.
  const Bytes wide = filtered_round_trip(meshopt_encodeFilterOct, normals, 8, 16, "OCTAHEDRAL");
  EXPECT_LT(max_error<std::int16_t>(normals, wide, 3), 2e-4); // measured: 5.9e-5
  // 8-bit components (stride 4): the error is a few 2^-7.
  const Bytes narrow = filtered_round_trip(meshopt_encodeFilterOct, normals, 4, 8, "OCTAHEDRAL");
  EXPECT_LT(max_error<std::int8_t>(normals, narrow, 3), 0.03); // measured: 0.017
}

TEST(MeshoptCodec, QuaternionFilterWithinItsPrecision) {
  std::vector<float> quaternions;
  const std::vector<float> axes = unit_vectors(100);
  for (std::size_t i = 0; i < 100; ++i) {
    const float half = 0.05f * float(i), s = std::sin(half);
    quaternions.insert(quaternions.end(),
                       {axes[4 * i] * s, axes[4 * i + 1] * s, axes[4 * i + 2] * s, std::cos(half)});
  }
  // 12-bit components: the error is about 2^-11 (q and -q are the same rotation: meshopt keeps
  // the sign of the largest component, so compare with that sign).
  const Bytes decoded =
      filtered_round_trip(meshopt_encodeFilterQuat, quaternions, 8, 12, "QUATERNION");
  const std::vector<std::int16_t> values = as<std::int16_t>(decoded);
  double worst = 0.0;
  for (std::size_t q = 0; q < 100; ++q) {
    double dot = 0.0;
    for (std::size_t c = 0; c < 4; ++c) dot += double(values[4 * q + c]) * quaternions[4 * q + c];
    const double sign = dot < 0.0 ? -1.0 : 1.0;
    for (std::size_t c = 0; c < 4; ++c) {
      const double v = sign * double(values[4 * q + c]) / 32767.0;
      worst = std::max(worst, std::abs(v - double(quaternions[4 * q + c])));
    }
  }
  EXPECT_LT(worst, 5e-4); // measured: 2.1e-4
}

TEST(MeshoptCodec, ExponentialFilterWithinItsPrecision) {
  std::vector<float> values;
  for (int i = 0; i < 64; ++i) {
    values.insert(values.end(), {float(i) * 3.7f - 50.0f, 1e-3f * float(i), 1234.5f, -0.5f});
  }
  // 16 bits of mantissa shared by the 4 components of an element (stride 16): the error is
  // below 2^-15 of the element's largest magnitude (measured: 2.5e-5 of it).
  const std::vector<float> decoded =
      as<float>(filtered_round_trip(meshopt_encodeFilterExp, values, 16, 16, "EXPONENTIAL"));
  ASSERT_EQ(decoded.size(), values.size());
  for (std::size_t e = 0; e < values.size() / 4; ++e) {
    float largest = 0.0f;
    for (std::size_t c = 0; c < 4; ++c) largest = std::max(largest, std::abs(values[4 * e + c]));
    for (std::size_t c = 0; c < 4; ++c) {
      EXPECT_NEAR(decoded[4 * e + c], values[4 * e + c], largest * 0x1p-15f) << e << ":" << c;
    }
  }
}

TEST(MeshoptCodec, RefusesLayoutsTheSpecificationForbids) {
  const std::vector<float> vertices(64, 1.0f);
  const Bytes v = irad::test::meshopt_encode_vertices(vertices.data(), 16, 16);
  const auto fails = [&](std::size_t count, std::size_t stride, const char* mode,
                         const char* filter) {
    EXPECT_THROW(decode_meshopt(v.data(), v.size(), count, stride, mode, filter), CodecError)
        << mode << " " << filter << " stride " << stride << " count " << count;
  };
  fails(16, 16, "VERTICES", "NONE");
  fails(16, 16, "ATTRIBUTES", "LINEAR");
  fails(16, 6, "ATTRIBUTES", "NONE");
  fails(16, 0, "ATTRIBUTES", "NONE");
  fails(16, 260, "ATTRIBUTES", "NONE");
  fails(16, 4, "TRIANGLES", "NONE");
  fails(16, 8, "INDICES", "NONE");
  fails(15, 1, "TRIANGLES", "NONE");
  fails(16, 4, "INDICES", "EXPONENTIAL");
  fails(16, 12, "ATTRIBUTES", "OCTAHEDRAL");
  fails(16, 4, "ATTRIBUTES", "QUATERNION");
  fails(std::numeric_limits<std::size_t>::max() / 8, 16, "ATTRIBUTES", "NONE");
}

TEST(MeshoptCodec, CorruptDataGiveCodecErrors) {
  const std::vector<float> vertices(400, 0.5f);
  const Bytes v = irad::test::meshopt_encode_vertices(vertices.data(), 100, 16);
  const irad::test::FixtureMesh cube = irad::test::cube_mesh();
  const Bytes t = irad::test::meshopt_encode_triangles(cube.indices, cube.vertex_count());
  const Bytes s = irad::test::meshopt_encode_sequence(cube.indices, cube.vertex_count());
  const std::size_t n = cube.indices.size();
  for (std::size_t cut : {std::size_t(0), std::size_t(1), v.size() / 2, v.size() - 1}) {
    EXPECT_THROW(decode_meshopt(v.data(), cut, 100, 16, "ATTRIBUTES", "NONE"), CodecError) << cut;
  }
  EXPECT_THROW(decode_meshopt(t.data(), t.size() - 1, n, 4, "TRIANGLES", "NONE"), CodecError);
  EXPECT_THROW(decode_meshopt(s.data(), s.size() - 1, n, 4, "INDICES", "NONE"), CodecError);
  EXPECT_THROW(decode_meshopt(nullptr, 0, 3, 4, "TRIANGLES", "NONE"), CodecError);
  // Random bytes after a valid header byte: either refused or decoded to the right size.
  for (unsigned seed = 0; seed < 50; ++seed) {
    using Case = std::tuple<const char*, int, int>;
    for (const auto& [mode, stride, header] :
         {Case{"ATTRIBUTES", 16, 0xA0}, Case{"TRIANGLES", 4, 0xE1}, Case{"INDICES", 4, 0xD1}}) {
      Bytes r = random_bytes(200 + seed * 7, seed);
      r[0] = static_cast<unsigned char>(header);
      try {
        EXPECT_EQ(decode_meshopt(r.data(), r.size(), 36, std::size_t(stride), mode, "NONE").size(),
                  36u * std::size_t(stride));
      } catch (const CodecError&) {
      }
    }
  }
}

// --- KHR_draco_mesh_compression ---

// 14-bit quantization of the cube's [-1, 1] positions: a step of 2 / (2^14 - 1), so an error of
// at most half that, 6.1e-5; uvs in [0, 1]: 3.1e-5. Normals (octahedral, 14 bits): the cube's
// axis-aligned normals come back within 1e-4.
constexpr float kPositionTolerance = 6.2e-5f;
constexpr float kUvTolerance = 3.1e-5f;
constexpr float kNormalTolerance = 1e-4f;

bool near3(const float* a, const float* b, float tolerance) {
  for (int c = 0; c < 3; ++c) {
    if (std::abs(a[c] - b[c]) > tolerance) return false;
  }
  return true;
}

TEST(DracoCodec, CubeRoundTrip) {
  const irad::test::FixtureMesh cube = irad::test::cube_mesh();
  const irad::test::DracoFixture fixture = irad::test::draco_encode(cube);
  const DracoMesh mesh(fixture.bytes.data(), fixture.bytes.size());
  ASSERT_EQ(mesh.vertex_count(), 24u);
  const std::vector<std::uint32_t> indices = mesh.indices();
  ASSERT_EQ(indices.size(), cube.indices.size());
  const auto positions = as<float>(mesh.attribute(fixture.position_id, 5126, 3, false));
  const auto normals = as<float>(mesh.attribute(fixture.normal_id, 5126, 3, false));
  const auto uvs = as<float>(mesh.attribute(fixture.texcoord_id, 5126, 2, false));
  ASSERT_EQ(positions.size(), 72u);
  ASSERT_EQ(uvs.size(), 48u);

  // Every decoded vertex is an input vertex (position, normal and uv together).
  for (std::size_t v = 0; v < 24; ++v) {
    bool found = false;
    for (std::size_t w = 0; w < 24 && !found; ++w) {
      found = near3(&positions[3 * v], &cube.positions[3 * w], kPositionTolerance) &&
              near3(&normals[3 * v], &cube.normals[3 * w], kNormalTolerance) &&
              std::abs(uvs[2 * v] - cube.uvs[2 * w]) <= kUvTolerance &&
              std::abs(uvs[2 * v + 1] - cube.uvs[2 * w + 1]) <= kUvTolerance;
    }
    EXPECT_TRUE(found) << "decoded vertex " << v;
  }
  // The faces as a set: each decoded triangle is one input triangle, same winding (a rotation
  // of its corners), each input triangle matched once.
  std::vector<bool> matched(cube.indices.size() / 3, false);
  for (std::size_t f = 0; f < indices.size() / 3; ++f) {
    bool found = false;
    for (std::size_t g = 0; g < matched.size() && !found; ++g) {
      for (std::size_t r = 0; r < 3 && !found; ++r) {
        bool same = true;
        for (std::size_t c = 0; c < 3; ++c) {
          same = same &&
                 near3(&positions[3 * indices[3 * f + c]],
                       &cube.positions[3 * cube.indices[3 * g + (c + r) % 3]], kPositionTolerance);
        }
        if (same && !matched[g]) found = matched[g] = true;
      }
    }
    EXPECT_TRUE(found) << "decoded face " << f;
  }
}

TEST(DracoCodec, ConvertsToNormalizedUnsignedShort) {
  const irad::test::FixtureMesh cube = irad::test::cube_mesh();
  const irad::test::DracoFixture fixture = irad::test::draco_encode(cube);
  const DracoMesh mesh(fixture.bytes.data(), fixture.bytes.size());
  const auto floats = as<float>(mesh.attribute(fixture.texcoord_id, 5126, 2, false));
  const auto shorts = as<std::uint16_t>(mesh.attribute(fixture.texcoord_id, 5123, 2, true));
  ASSERT_EQ(shorts.size(), floats.size());
  for (std::size_t i = 0; i < shorts.size(); ++i) {
    // The glTF conversion of the dequantized value, exactly; and the input's 0 or 1 within the
    // 14-bit quantization (3.1e-5 * 65535 = 2.0).
    EXPECT_EQ(shorts[i], std::lround(std::clamp(floats[i], 0.0f, 1.0f) * 65535.0f)) << i;
    EXPECT_TRUE(shorts[i] <= 2 || shorts[i] >= 65533) << shorts[i];
  }
  // Signed normalized: normals in [-1, 1] as shorts.
  const auto normals = as<std::int16_t>(mesh.attribute(fixture.normal_id, 5122, 3, true));
  for (const std::int16_t n : normals) EXPECT_TRUE(std::abs(n) <= 4 || std::abs(n) >= 32763) << n;
}

TEST(DracoCodec, RefusesWrongRequests) {
  const irad::test::DracoFixture fixture = irad::test::draco_encode(irad::test::cube_mesh());
  const DracoMesh mesh(fixture.bytes.data(), fixture.bytes.size());
  EXPECT_THROW(mesh.attribute(99, 5126, 3, false), CodecError);
  EXPECT_THROW(mesh.attribute(-1, 5126, 3, false), CodecError);
  EXPECT_THROW(mesh.attribute(fixture.position_id, 5126, 4, false), CodecError);
  EXPECT_THROW(mesh.attribute(fixture.position_id, 5124, 3, false), CodecError);
  // Positions up to 1 fit unsigned bytes only when rounded; -1 does not.
  EXPECT_THROW(mesh.attribute(fixture.position_id, 5121, 3, false), CodecError);
}

TEST(DracoCodec, CorruptDataGiveCodecErrorsNeverACrash) {
  const irad::test::DracoFixture fixture = irad::test::draco_encode(irad::test::cube_mesh());
  const Bytes& good = fixture.bytes;
  EXPECT_THROW(DracoMesh(nullptr, 0), CodecError);
  for (std::size_t cut : {std::size_t(1), std::size_t(5), good.size() / 2, good.size() - 1}) {
    EXPECT_THROW(DracoMesh(good.data(), cut), CodecError) << cut;
  }
  const Bytes noise = random_bytes(300, 7);
  EXPECT_THROW(DracoMesh(noise.data(), noise.size()), CodecError);
  // Flipped bytes past the header: refused, or decoded into something whose every answer is
  // either a value or a CodecError.
  for (unsigned seed = 0; seed < 200; ++seed) {
    Bytes bad = good;
    std::mt19937 rng(seed);
    for (int k = 0; k < 3; ++k) {
      bad[16 + rng() % (bad.size() - 16)] ^= static_cast<unsigned char>(1u << (rng() % 8));
    }
    try {
      const DracoMesh mesh(bad.data(), bad.size());
      (void)mesh.indices();
      (void)mesh.attribute(fixture.position_id, 5126, 3, false);
      (void)mesh.attribute(fixture.texcoord_id, 5123, 2, true);
    } catch (const CodecError&) {
    }
  }
}

TEST(DracoCodec, Moves) {
  const irad::test::DracoFixture fixture = irad::test::draco_encode(irad::test::cube_mesh());
  DracoMesh a(fixture.bytes.data(), fixture.bytes.size());
  DracoMesh b = std::move(a);
  EXPECT_EQ(b.vertex_count(), 24u);
  a = std::move(b);
  EXPECT_EQ(a.vertex_count(), 24u);
}

// --- Images ---

// A w x h image with `channels` channels of 8 bits, each texel distinct.
Bytes test_pixels(int w, int h, int channels) {
  Bytes out(std::size_t(w * h * channels));
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = static_cast<unsigned char>(i * 37 + 11);
  return out;
}

void append(void* context, void* data, int size) {
  auto& out = *static_cast<Bytes*>(context);
  const auto* first = static_cast<const unsigned char*>(data);
  out.insert(out.end(), first, first + size);
}

Bytes png_of(const Bytes& pixels, int w, int h, int channels) {
  Bytes out;
  stbi_write_png_to_func(append, &out, w, h, channels, pixels.data(), w * channels);
  return out;
}

std::uint32_t crc32(const unsigned char* data, std::size_t size) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void put32(Bytes& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8)
    out.push_back(static_cast<unsigned char>(v >> shift));
}

void chunk(Bytes& png, const char* type, const Bytes& data) {
  put32(png, std::uint32_t(data.size()));
  Bytes typed(type, type + 4);
  typed.insert(typed.end(), data.begin(), data.end());
  png.insert(png.end(), typed.begin(), typed.end());
  put32(png, crc32(typed.data(), typed.size()));
}

// A PNG written by hand (stb_image_write writes 8 bits only): colour type 0 (grey) or 2 (RGB),
// `bits` 8 or 16, the rows (big-endian samples) in one stored zlib block, and optionally a tRNS
// chunk or an empty IDAT chunk first.
Bytes handmade_png(int w, int h, int colour_type, int bits, const Bytes& samples, bool trns,
                   bool empty_idat = false) {
  Bytes png{0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  Bytes ihdr;
  put32(ihdr, std::uint32_t(w));
  put32(ihdr, std::uint32_t(h));
  ihdr.insert(ihdr.end(),
              {static_cast<unsigned char>(bits), static_cast<unsigned char>(colour_type), 0, 0, 0});
  chunk(png, "IHDR", ihdr);
  if (trns) chunk(png, "tRNS", Bytes(colour_type == 0 ? 2 : 6, 0)); // key: black
  if (empty_idat) chunk(png, "IDAT", {});
  const std::size_t row = samples.size() / std::size_t(h);
  Bytes raw;
  for (std::size_t y = 0; y < std::size_t(h); ++y) {
    raw.push_back(0); // filter: none
    raw.insert(raw.end(), samples.begin() + std::ptrdiff_t(y * row),
               samples.begin() + std::ptrdiff_t((y + 1) * row));
  }
  Bytes z{0x78, 0x01, 1}; // zlib header, a final stored block
  const auto n = static_cast<std::uint16_t>(raw.size());
  z.insert(z.end(),
           {static_cast<unsigned char>(n & 0xFF), static_cast<unsigned char>(n >> 8),
            static_cast<unsigned char>(~n & 0xFF), static_cast<unsigned char>((~n >> 8) & 0xFF)});
  z.insert(z.end(), raw.begin(), raw.end());
  std::uint32_t a = 1, b = 0;
  for (const unsigned char c : raw) {
    a = (a + c) % 65521;
    b = (b + a) % 65521;
  }
  put32(z, b << 16 | a);
  chunk(png, "IDAT", z);
  chunk(png, "IEND", {});
  return png;
}

TEST(ImageDecode, SniffsAndNamesFormats) {
  const Bytes png = png_of(test_pixels(2, 2, 3), 2, 2, 3);
  EXPECT_EQ(irad::gltf::sniff_image(png.data(), png.size()), ImageFormat::Png);
  const unsigned char jpeg[] = {0xFF, 0xD8, 0xFF, 0xE0};
  EXPECT_EQ(irad::gltf::sniff_image(jpeg, sizeof jpeg), ImageFormat::Jpeg);
  const unsigned char webp[] = {'R', 'I', 'F', 'F', 1, 2, 3, 4, 'W', 'E', 'B', 'P'};
  EXPECT_EQ(irad::gltf::sniff_image(webp, sizeof webp), ImageFormat::Webp);
  EXPECT_EQ(irad::gltf::sniff_image(webp, 11), ImageFormat::Unknown);
  EXPECT_EQ(irad::gltf::sniff_image(png.data(), 7), ImageFormat::Unknown);
  EXPECT_STREQ(irad::gltf::image_format_name(ImageFormat::Webp), "WebP");
  EXPECT_STREQ(irad::gltf::image_format_name(ImageFormat::Unknown), "unknown");
  EXPECT_THROW(decode_image(jpeg, 2, {}), ImageError);
}

TEST(ImageDecode, Png8BitExactly) {
  for (const int channels : {1, 2, 3, 4}) {
    const Bytes pixels = test_pixels(5, 3, channels);
    const Bytes png = png_of(pixels, 5, 3, channels);
    const DecodedImage image = decode_image(png.data(), png.size(), {});
    EXPECT_EQ(image.width, 5);
    EXPECT_EQ(image.height, 3);
    EXPECT_EQ(image.channels, channels);
    EXPECT_EQ(image.bits, 8);
    EXPECT_EQ(image.pixels, pixels) << channels;
  }
}

TEST(ImageDecode, Png16BitAsSixteenBits) {
  const std::vector<std::uint16_t> values{0, 1,     256,   65535, 4660, 43981,
                                          7, 30000, 65534, 12,    13,   14};
  Bytes big_endian;
  for (const std::uint16_t v : values) {
    big_endian.insert(big_endian.end(),
                      {static_cast<unsigned char>(v >> 8), static_cast<unsigned char>(v & 0xFF)});
  }
  const Bytes png = handmade_png(2, 2, 2, 16, big_endian, false);
  const DecodedImage image = decode_image(png.data(), png.size(), {});
  EXPECT_EQ(image.channels, 3);
  EXPECT_EQ(image.bits, 16);
  EXPECT_EQ(as<std::uint16_t>(image.pixels), values);
}

TEST(ImageDecode, PngColourKeyBecomesAlpha) {
  const Bytes grey{0, 50, 100, 0};
  const Bytes png = handmade_png(2, 2, 0, 8, grey, true);
  const DecodedImage image = decode_image(png.data(), png.size(), {});
  EXPECT_EQ(image.channels, 2);
  EXPECT_EQ(image.pixels, (Bytes{0, 0, 50, 255, 100, 255, 0, 0}));
}

TEST(ImageDecode, PngWithAnEmptyIdatIsRefused) {
  const Bytes png = handmade_png(2, 2, 0, 8, Bytes(4, 9), false, true);
  EXPECT_THROW(decode_image(png.data(), png.size(), {}), ImageError);
}

TEST(ImageDecode, JpegDecodes) {
  Bytes pixels(16 * 8 * 3);
  for (std::size_t i = 0; i < pixels.size(); i += 3) {
    pixels[i] = 200;
    pixels[i + 1] = 100;
    pixels[i + 2] = 50;
  }
  Bytes jpeg;
  stbi_write_jpg_to_func(append, &jpeg, 16, 8, 3, pixels.data(), 95);
  const DecodedImage image = decode_image(jpeg.data(), jpeg.size(), {});
  EXPECT_EQ(image.width, 16);
  EXPECT_EQ(image.height, 8);
  EXPECT_EQ(image.channels, 3);
  ASSERT_EQ(image.pixels.size(), pixels.size());
  // A flat colour at quality 95: within 3 levels of 255 per channel.
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    EXPECT_NEAR(int(image.pixels[i]), int(pixels[i]), 3) << i;
  }
}

Bytes webp_lossless(const Bytes& pixels, int w, int h, bool alpha) {
  std::uint8_t* out = nullptr;
  const std::size_t size = alpha ? WebPEncodeLosslessRGBA(pixels.data(), w, h, w * 4, &out)
                                 : WebPEncodeLosslessRGB(pixels.data(), w, h, w * 3, &out);
  Bytes bytes(out, out + size);
  WebPFree(out);
  return bytes;
}

TEST(ImageDecode, WebpLosslessExactly) {
  const Bytes rgba = test_pixels(7, 5, 4);
  const Bytes webp = webp_lossless(rgba, 7, 5, true);
  ASSERT_FALSE(webp.empty());
  const DecodedImage image = decode_image(webp.data(), webp.size(), {});
  EXPECT_EQ(image.width, 7);
  EXPECT_EQ(image.height, 5);
  EXPECT_EQ(image.channels, 4);
  EXPECT_EQ(image.pixels, rgba);

  const Bytes rgb = test_pixels(6, 4, 3);
  const Bytes opaque = webp_lossless(rgb, 6, 4, false);
  const DecodedImage decoded = decode_image(opaque.data(), opaque.size(), {});
  EXPECT_EQ(decoded.channels, 3);
  EXPECT_EQ(decoded.pixels, rgb);
}

TEST(ImageDecode, LimitsRefuseOversizedImagesBeforeDecoding) {
  // Only the headers are real: the pixel data are cut off, so a decode would fail differently.
  const Bytes png = png_of(test_pixels(64, 32, 3), 64, 32, 3);
  const Bytes png_header(png.begin(), png.begin() + 33);
  const Bytes webp = webp_lossless(test_pixels(64, 32, 4), 64, 32, true);
  const Bytes webp_header(webp.begin(), webp.begin() + 30);
  for (const Bytes* bytes : {&png_header, &webp_header}) {
    try {
      decode_image(bytes->data(), bytes->size(), ImageLimits{32, 1u << 20});
      ADD_FAILURE() << "not refused";
    } catch (const ImageError& e) {
      EXPECT_STREQ(e.what(), "64 x 32 texels exceed --max-texture-size 32");
    }
    EXPECT_THROW(decode_image(bytes->data(), bytes->size(), ImageLimits{64, 2047}), ImageError);
  }
}

TEST(ImageDecode, CorruptDataGiveImageErrorsNeverACrash) {
  const Bytes png = png_of(test_pixels(9, 9, 4), 9, 9, 4);
  const Bytes webp = webp_lossless(test_pixels(9, 9, 4), 9, 9, true);
  Bytes jpeg;
  const Bytes rgb = test_pixels(9, 9, 3);
  stbi_write_jpg_to_func(append, &jpeg, 9, 9, 3, rgb.data(), 90);
  for (const Bytes* good : std::array<const Bytes*, 3>{&png, &webp, &jpeg}) {
    for (const std::size_t cut : {std::size_t(12), good->size() / 2, good->size() - 8}) {
      if (good == &jpeg && cut > 12) {
        // stb_image decodes a truncated JPEG's missing data as zeros: a full image, or refused.
        try {
          EXPECT_EQ(decode_image(good->data(), cut, {}).pixels.size(), rgb.size());
        } catch (const ImageError&) {
        }
      } else {
        EXPECT_THROW(decode_image(good->data(), cut, {}), ImageError) << cut;
      }
    }
    // Noise after the signature: an ImageError, never a crash.
    Bytes noisy = *good;
    const Bytes noise = random_bytes(noisy.size(), 3);
    std::copy(noise.begin() + 16, noise.end(), noisy.begin() + 16);
    try {
      (void)decode_image(noisy.data(), noisy.size(), {});
    } catch (const ImageError& e) {
      EXPECT_EQ(std::string(e.what()).find("stb"), std::string::npos) << e.what();
    }
  }
  try {
    (void)decode_image(png.data(), png.size() / 2, {});
  } catch (const ImageError& e) {
    EXPECT_STREQ(e.what(), "the PNG does not decode (corrupt data)");
  }
}

} // namespace
