#pragma once
// Shared by the libFuzzer target (fuzz/gltf_loader_fuzzer.cpp) and the corpus replay test
// (tests/test_fuzz_corpus.cpp): how one fuzz input becomes a scene file and is loaded.
//
// The input is written to DIR/scene.glb when it starts with the GLB magic "glTF", else to
// DIR/scene.gltf, and loaded with kFuzzLimits. DIR also holds two files that inputs may name as
// external URIs: buffer.bin (64 bytes: 16 floats) and image.png (a 2x2 RGBA PNG).
#include "core/gltf/loader.h"
#include "core/scene/scene.h"
#include "core/util/error.h"
#include "core/util/log.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

namespace irad::fuzz {

// Small limits: the fuzzer's inputs are a few KB, and large allocations only slow it down.
inline LoadLimits fuzz_limits() {
  LoadLimits l;
  l.max_file_bytes = 1 << 20;
  l.max_triangles = 1 << 16;
  l.max_texture_size = 256;
  l.max_texture_texels = 1 << 18;
  return l;
}

inline void write_bytes(const std::filesystem::path& path, const void* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
}

// A 2x2 RGBA PNG (stored deflate), red green / blue white.
inline const unsigned char kPng[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
    0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x06, 0x00, 0x00, 0x00, 0x72,
    0xb6, 0x0d, 0x24, 0x00, 0x00, 0x00, 0x1d, 0x49, 0x44, 0x41, 0x54, 0x78, 0x01, 0x01, 0x12,
    0x00, 0xed, 0xff, 0x00, 0xff, 0x00, 0x00, 0xff, 0x00, 0xff, 0x00, 0xff, 0x00, 0x00, 0x00,
    0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x49, 0xc8, 0x09, 0xf7, 0xad, 0xab, 0x56, 0x1b, 0x00,
    0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

// Creates DIR and the external files inputs may refer to.
inline void prepare_dir(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  float floats[16] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 0};
  write_bytes(dir / "buffer.bin", floats, sizeof floats);
  write_bytes(dir / "image.png", kPng, sizeof kPng);
}

// Invariants of every scene the loader returns; a violation is a loader bug.
inline bool scene_is_consistent(const Scene& s) {
  const std::size_t n = s.positions.size();
  if (s.normals.size() != n || (!s.uvs.empty() && s.uvs.size() != n)) return false;
  if (s.triangles.empty() || s.triangle_material.size() != s.triangles.size()) return false;
  for (const glm::uvec3& t : s.triangles) {
    if (t.x >= n || t.y >= n || t.z >= n) return false;
  }
  for (std::uint32_t m : s.triangle_material) {
    if (m >= s.materials.size()) return false;
  }
  for (std::size_t v = 0; v < n; ++v) {
    const glm::vec3 p = s.positions[v];
    const glm::vec3 nn = s.normals[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
    if (!(std::fabs(glm::length(nn) - 1.0f) < 1e-3f)) return false;
  }
  for (const Material& m : s.materials) {
    if (m.base_color_texture >= int(s.textures.size())) return false;
    if (m.emissive_texture >= int(s.textures.size())) return false;
  }
  for (const Texture& t : s.textures) {
    if (t.width < 1 || t.height < 1 ||
        t.texels.size() != std::size_t(t.width) * std::size_t(t.height))
      return false;
  }
  return !s.cameras.empty();
}

// Writes the input into dir and loads it. Returns true when it loaded, false on irad::Error;
// anything else (another exception, a crash, a failed invariant: abort) is a bug.
inline bool load_input(const std::filesystem::path& dir, const std::uint8_t* data,
                       std::size_t size) {
  const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::filesystem::path path = dir / (glb ? "scene.glb" : "scene.gltf");
  write_bytes(path, data, size);
  Log log([](const std::string&) {});
  try {
    const Scene scene = load_gltf(path, log, fuzz_limits());
    if (!scene_is_consistent(scene)) std::abort();
    return true;
  } catch (const Error&) {
    return false;
  }
}

} // namespace irad::fuzz
