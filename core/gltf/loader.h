#pragma once
// glTF 2.0 (.gltf and .glb) to irad::Scene through tinygltf 2.7.
// Supported: node hierarchy (TRS or matrix; normals by the inverse transpose), triangle
// primitives (indexed u8/u16/u32 or not), POSITION, NORMAL (flat normals when absent),
// TEXCOORD_0; materials (baseColorFactor, baseColorTexture decoded from sRGB, emissiveFactor x
// KHR_materials_emissive_strength, emissiveTexture, doubleSided; mirrors where metallicFactor >=
// 0.9 and roughnessFactor <= 0.1, core/gltf/materials.h); perspective cameras;
// KHR_lights_punctual point and spot lights. Only the default scene (or scene 0) is loaded.
// Every error throws irad::Error("FILE", "ELEMENT", "MESSAGE"), e.g. "box.gltf: accessors[3]: ...";
// docs/errors.md lists them. Before tinygltf sees a byte, the file is checked (size, GLB header
// and chunks, JSON syntax and nesting depth, buffer and image URIs: data URIs must be base64,
// external files must lie in the scene's folder and hold byteLength bytes), so that no input
// makes the loader crash, hang or allocate beyond the limits below. Triangles with a NaN or Inf
// vertex position are dropped with one warning.
#include "core/log.h"
#include "core/scene.h"

#include <cstdint>
#include <filesystem>
#include <string>

namespace irad {

// Resource limits: a scene beyond one is an error naming the limit, never an out-of-memory kill.
struct LoadLimits {
  // Bytes of the scene file and of each external file it names (--max-file-size, in MiB); the
  // scene file is also limited to 4 GiB - 1 (tinygltf's sizes are 32-bit).
  std::uint64_t max_file_bytes = std::uint64_t(1) << 30;
  // Triangles of the scene, all instances together (--max-triangles). Vertices, and the elements
  // of one accessor, may be three times as many.
  std::uint64_t max_triangles = std::uint64_t(1) << 24;
  // Texels per side of one image (--max-texture-size).
  int max_texture_size = 8192;
  // Decoded texels of all images together (4 floats each in memory).
  std::uint64_t max_texture_texels = std::uint64_t(1) << 26;
  // Nesting depth of JSON arrays and objects.
  int max_json_depth = 64;
};

// `scene`: the glTF scene to load, by name or index (empty: the file's default scene).
Scene load_gltf(const std::filesystem::path& path, Log& log, const LoadLimits& limits = {},
                const std::string& scene = {});

} // namespace irad
