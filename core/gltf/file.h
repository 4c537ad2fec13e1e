#pragma once
// Internal to the glTF loader: the scene file, read and checked before tinygltf parses it, so that
// every bad input gets one message naming the element (docs/errors.md) and tinygltf never meets
// input it mishandles (deep JSON nesting, GLB chunks beyond the file, empty buffers, negative
// offsets it would read as absent, URIs outside the scene's folder, images too large to decode).
#include "core/gltf/loader.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace irad::gltf {

struct SceneFile {
  std::vector<unsigned char> bytes; // the file; a GLB ends where its header's length says
  bool binary = false;              // GLB
  std::size_t json_offset = 0;      // the JSON text within bytes
  std::size_t json_length = 0;
  std::size_t bin_length = 0; // GLB: payload bytes of the BIN chunk (0: none)
};

// Reads `path` and checks, failing with Error(file, element, message): that it can be read, is
// not empty and within limits.max_file_bytes; a GLB's header and chunks; that the JSON parses, is
// nested at most limits.max_json_depth deep and is an object with asset.version; that indices,
// offsets and counts are non-negative integers; that every buffer and image has its data (data
// URIs in base64, external files inside the scene's folder, byteLength bytes for buffers).
SceneFile read_scene_file(const std::filesystem::path& path, const std::string& file,
                          const LoadLimits& limits);

// Reads a whole file of at most `max_bytes` bytes, failing with Error(file, element, ...).
std::vector<unsigned char> read_file_limited(const std::filesystem::path& path,
                                             std::uint64_t max_bytes, const std::string& file,
                                             const std::string& element);

// Fails unless the image bytes are a PNG or JPEG whose size is within the limits; adds its texels
// to `texels` (the running total of the scene's images).
void check_image_bytes(const std::string& file, const std::string& element,
                       const unsigned char* bytes, std::size_t size, const LoadLimits& limits,
                       std::uint64_t& texels);

} // namespace irad::gltf
