#pragma once
// glTF scenes written from C++ for the loader tests (test_gltf_loader.cpp, test_bad_input.cpp):
// JSON through nlohmann::json, buffers as base64 data URIs, .bin files or GLB chunks, images as
// hand-written (stored-deflate) PNGs.
#include "core/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace gltf_test {

using json = nlohmann::json;
namespace fs = std::filesystem;

constexpr int kU8 = 5121;
constexpr int kU16 = 5123;
constexpr int kU32 = 5125;
constexpr int kFloat = 5126;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// ---------------------------------------------------------------------------------------------
// Encoders

inline std::string base64(const std::vector<unsigned char>& bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 3; ++k) v = (v << 8) | (k < n ? bytes[i + k] : 0u);
    for (std::size_t k = 0; k < 4; ++k) {
      out += k <= n ? kAlphabet[(v >> (18 - 6 * k)) & 63u] : '=';
    }
  }
  return out;
}

inline void put_be32(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8)
    out.push_back(static_cast<unsigned char>(v >> shift));
}

inline void put_le32(std::vector<unsigned char>& out, std::uint32_t v) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back(static_cast<unsigned char>(v >> shift));
}

inline std::uint32_t crc32(const std::vector<unsigned char>& data) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (unsigned char byte : data) {
    crc ^= byte;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

inline void put_chunk(std::vector<unsigned char>& png, const char* type,
                      const std::vector<unsigned char>& data) {
  put_be32(png, static_cast<std::uint32_t>(data.size()));
  std::vector<unsigned char> body(type, type + 4);
  body.insert(body.end(), data.begin(), data.end());
  png.insert(png.end(), body.begin(), body.end());
  put_be32(png, crc32(body));
}

// zlib stream of stored (uncompressed) deflate blocks.
inline std::vector<unsigned char> zlib_stored(const std::vector<unsigned char>& raw) {
  std::vector<unsigned char> out{0x78, 0x01};
  std::size_t pos = 0;
  do {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - pos);
    out.push_back(pos + n == raw.size() ? 1 : 0);
    const auto len = static_cast<std::uint16_t>(n);
    const auto nlen = static_cast<std::uint16_t>(~len);
    out.insert(out.end(),
               {static_cast<unsigned char>(len & 0xFF), static_cast<unsigned char>(len >> 8),
                static_cast<unsigned char>(nlen & 0xFF), static_cast<unsigned char>(nlen >> 8)});
    out.insert(out.end(), raw.begin() + static_cast<long>(pos),
               raw.begin() + static_cast<long>(pos + n));
    pos += n;
  } while (pos < raw.size());
  std::uint32_t a = 1, b = 0;
  for (unsigned char c : raw) {
    a = (a + c) % 65521u;
    b = (b + a) % 65521u;
  }
  put_be32(out, (b << 16) | a);
  return out;
}

// PNG of w x h pixels with 1-4 channels (grey, grey+alpha, RGB, RGBA) of 8 or 16 bits; samples
// row-major, top row first.
inline std::vector<unsigned char> png(int w, int h, int channels, int bits,
                                      const std::vector<std::uint16_t>& samples) {
  static constexpr unsigned char kColourType[] = {0, 0, 4, 2, 6};
  std::vector<unsigned char> out{0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  std::vector<unsigned char> ihdr;
  put_be32(ihdr, static_cast<std::uint32_t>(w));
  put_be32(ihdr, static_cast<std::uint32_t>(h));
  ihdr.insert(ihdr.end(), {static_cast<unsigned char>(bits), kColourType[channels], 0, 0, 0});
  put_chunk(out, "IHDR", ihdr);
  std::vector<unsigned char> raw;
  const std::size_t row = static_cast<std::size_t>(w * channels);
  for (std::size_t y = 0; y < static_cast<std::size_t>(h); ++y) {
    raw.push_back(0); // filter: none
    for (std::size_t k = 0; k < row; ++k) {
      const std::uint16_t s = samples[y * row + k];
      if (bits == 16) raw.push_back(static_cast<unsigned char>(s >> 8));
      raw.push_back(static_cast<unsigned char>(s & 0xFF));
    }
  }
  put_chunk(out, "IDAT", zlib_stored(raw));
  put_chunk(out, "IEND", {});
  return out;
}

inline void write_file(const fs::path& path, const void* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
}

inline void write_file(const fs::path& path, const std::string& text) {
  write_file(path, text.data(), text.size());
}

// ---------------------------------------------------------------------------------------------
// A glTF document under construction with one binary buffer (buffers[0]).

class Gltf {
public:
  json doc = {{"asset", {{"version", "2.0"}}}};
  std::vector<unsigned char> bin;

  int push(const char* array, json value) {
    doc[array].push_back(std::move(value));
    return static_cast<int>(doc[array].size()) - 1;
  }

  // Appends bytes (4-byte aligned) as a new bufferView.
  int view(const void* data, std::size_t size, int stride = 0) {
    while (bin.size() % 4 != 0) bin.push_back(0);
    const std::size_t offset = bin.size();
    const auto* bytes = static_cast<const unsigned char*>(data);
    bin.insert(bin.end(), bytes, bytes + size);
    json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}};
    if (stride != 0) v["byteStride"] = stride;
    return push("bufferViews", v);
  }

  int accessor(int view_index, int component_type, std::size_t count, const std::string& type,
               const json& extra = json::object()) {
    json a = {{"bufferView", view_index},
              {"componentType", component_type},
              {"count", count},
              {"type", type}};
    a.update(extra);
    return push("accessors", a);
  }

  int vec3s(const std::vector<glm::vec3>& v) {
    return accessor(view(v.data(), v.size() * sizeof(glm::vec3)), kFloat, v.size(), "VEC3");
  }

  // A POSITION accessor: VEC3 floats with the min and max glTF requires (over the finite
  // components; a component with none gets 0).
  int positions(const std::vector<glm::vec3>& v) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& p : v)
      for (int k = 0; k < 3; ++k)
        if (std::isfinite(p[k])) {
          lo[k] = std::min(lo[k], p[k]);
          hi[k] = std::max(hi[k], p[k]);
        }
    for (int k = 0; k < 3; ++k)
      if (lo[k] > hi[k]) lo[k] = hi[k] = 0.0f;
    return accessor(view(v.data(), v.size() * sizeof(glm::vec3)), kFloat, v.size(), "VEC3",
                    {{"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}});
  }

  int vec2s(const std::vector<glm::vec2>& v) {
    return accessor(view(v.data(), v.size() * sizeof(glm::vec2)), kFloat, v.size(), "VEC2");
  }

  template <class T>
  int indices(const std::vector<T>& v) {
    const int type = sizeof(T) == 1 ? kU8 : sizeof(T) == 2 ? kU16 : kU32;
    return accessor(view(v.data(), v.size() * sizeof(T)), type, v.size(), "SCALAR");
  }

  int image_png(const std::vector<unsigned char>& bytes) {
    return push("images",
                {{"bufferView", view(bytes.data(), bytes.size())}, {"mimeType", "image/png"}});
  }

  // buffers[0] as a base64 data URI.
  fs::path write_gltf(const fs::path& path) const {
    json d = doc;
    d["buffers"] = json::array({{{"byteLength", bin.size()},
                                 {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
    write_file(path, d.dump(1));
    return path;
  }

  // buffers[0] as an external .bin file next to the .gltf.
  fs::path write_gltf_bin(const fs::path& path) const {
    const fs::path bin_path = fs::path(path).replace_extension(".bin");
    write_file(bin_path, bin.data(), bin.size());
    json d = doc;
    d["buffers"] =
        json::array({{{"byteLength", bin.size()}, {"uri", bin_path.filename().string()}}});
    write_file(path, d.dump(1));
    return path;
  }

  // GLB container: 12-byte header, JSON chunk (space-padded), BIN chunk (zero-padded).
  fs::path write_glb(const fs::path& path, const char* magic = "glTF") const {
    json d = doc;
    d["buffers"] = json::array({{{"byteLength", bin.size()}}});
    std::string text = d.dump();
    while (text.size() % 4 != 0) text += ' ';
    std::vector<unsigned char> body = bin;
    while (body.size() % 4 != 0) body.push_back(0);
    std::vector<unsigned char> out(magic, magic + 4);
    put_le32(out, 2);
    put_le32(out, static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + body.size()));
    put_le32(out, static_cast<std::uint32_t>(text.size()));
    put_le32(out, 0x4E4F534Au); // "JSON"
    out.insert(out.end(), text.begin(), text.end());
    put_le32(out, static_cast<std::uint32_t>(body.size()));
    put_le32(out, 0x004E4942u); // "BIN\0"
    out.insert(out.end(), body.begin(), body.end());
    write_file(path, out.data(), out.size());
    return path;
  }
};

// Unit quad in z = 0 facing +z: vertices (0,0,0) (1,0,0) (1,1,0) (0,1,0), triangles 012, 023.
inline const std::vector<glm::vec3> kQuad{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
inline const std::vector<std::uint16_t> kQuadIndices{0, 1, 2, 0, 2, 3};

inline json quad_primitive(Gltf& g, int material, const std::vector<glm::vec3>& normals) {
  json p = {{"attributes", {{"POSITION", g.positions(kQuad)}}},
            {"indices", g.indices(kQuadIndices)}};
  if (!normals.empty()) p["attributes"]["NORMAL"] = g.vec3s(normals);
  if (material >= 0) p["material"] = material;
  return p;
}

inline const std::vector<glm::vec3> kUpNormals(4, glm::vec3(0, 0, 1));

// One node with the quad, lit by an emissive material (materials[0]).
inline Gltf emissive_quad(json node = json::object()) {
  Gltf g;
  g.push("materials", {{"emissiveFactor", {1.0, 1.0, 1.0}}});
  g.push("meshes", {{"primitives", {quad_primitive(g, 0, kUpNormals)}}});
  node["mesh"] = 0;
  g.push("nodes", node);
  g.doc["scenes"] = {{{"nodes", {0}}}};
  g.doc["scene"] = 0;
  return g;
}

inline void expect_near(const glm::vec3& a, const glm::vec3& b, float tol = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

inline void expect_near(const glm::vec4& a, const glm::vec4& b, float tol = 1e-5f) {
  expect_near(glm::vec3(a), glm::vec3(b), tol);
  EXPECT_NEAR(a.w, b.w, tol);
}

// Corner positions of every triangle, in order.
inline std::vector<glm::vec3> corners(const irad::Scene& s) {
  std::vector<glm::vec3> out;
  for (const glm::uvec3& t : s.triangles) {
    out.insert(out.end(), {s.positions[t.x], s.positions[t.y], s.positions[t.z]});
  }
  return out;
}

} // namespace gltf_test
