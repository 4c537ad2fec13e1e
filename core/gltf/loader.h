#pragma once
// glTF 2.0 (.gltf and .glb) to irad::Scene, read with irad's own JSON reader (nlohmann::json).
// Supported (docs/gltf.md has the whole table): node hierarchy (TRS or matrix; normals by the
// inverse transpose), triangle primitives (indexed u8/u16/u32 or not; strips and fans),
// POSITION, NORMAL (flat normals when absent), TEXCOORD_n (two sets per material), COLOR_0,
// KHR_mesh_quantization, sparse accessors, KHR_draco_mesh_compression, EXT_meshopt_compression;
// skins and morph targets at rest (default weights); materials (baseColorFactor and
// baseColorTexture decoded from sRGB, alphaMode and alphaCutoff, emissiveFactor x
// KHR_materials_emissive_strength, emissiveTexture, doubleSided, KHR_texture_transform,
// EXT_texture_webp; mirrors where metallicFactor >= 0.9 and roughnessFactor <= 0.1,
// core/gltf/read/materials.h); perspective and orthographic cameras; KHR_lights_punctual lights.
//
// Validation (core/gltf/validate/validate.h): the document is checked as the Khronos glTF-Validator
// checks it. A problem in an element irad uses is the error of the file, named by its JSON path
// ("meshes[2].primitives[0].attributes.NORMAL: ..."); problems irad repairs (a non-unit
// rotation, missing POSITION bounds, ...) are warnings; problems in elements irad does not use
// are one warning line that counts them. An unsupported extension is a warning, or an error when
// the file lists it in extensionsRequired. Every error throws irad::Error("FILE", "ELEMENT",
// "MESSAGE") in irad's own words (docs/errors.md); no input makes the loader crash, hang or
// allocate beyond the limits below. Triangles with a NaN or Inf vertex position are dropped with
// one warning.
#include "core/scene/scene.h"
#include "core/util/log.h"

#include <cstdint>
#include <filesystem>
#include <string>

namespace irad {

// Resource limits: a scene beyond one is an error naming the limit, never an out-of-memory kill.
struct LoadLimits {
  // Bytes of the scene file and of each external file it names (--max-file-size, in MiB); the
  // scene file is also limited to 4 GiB - 1 (GLB lengths are 32-bit).
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
