#pragma once
// Internal to the glTF loader: the scene file read and parsed (file-level errors: unreadable,
// empty, beyond the size limit, a broken GLB container, JSON that does not parse or nests too
// deep, no asset.version 2.x), and the data its buffers and images name (data URIs in base64,
// external files inside the scene's folder, the GLB BIN chunk), whose problems are validator
// issues of those elements rather than errors: a buffer nobody uses may lack its data.
#include "core/gltf/context.h"
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
  std::size_t bin_offset = 0; // GLB: the BIN chunk's payload within bytes
  std::size_t bin_length = 0; // (0: none)
  json root;                  // the parsed JSON, an object with asset.version "2.x"
};

// Reads and parses `path`, failing with Error(file, element, message) on file-level problems.
SceneFile read_scene_file(const std::filesystem::path& path, const std::string& file,
                          const LoadLimits& limits);

// The data of every buffer; what cannot be had is an issue of "/buffers/i" in `issues`.
std::vector<BufferData> resolve_buffers(SceneFile& f, const std::filesystem::path& folder,
                                        const LoadLimits& limits, IssueBook& issues);

// The bytes an image or buffer URI names: a base64 data URI (whose media type must be one of
// `media`, e.g. "image/png") or an external file inside `folder` of at most limits'
// max_file_bytes. Fails with Error(file, where, ...).
std::vector<unsigned char> uri_bytes(const std::string& uri,
                                     std::initializer_list<std::string_view> media,
                                     const std::filesystem::path& folder, const LoadLimits& limits,
                                     const std::string& file, const std::string& where);

// Reads a whole file of at most `max_bytes` bytes, failing with Error(file, element, ...).
std::vector<unsigned char> read_file_limited(const std::filesystem::path& path,
                                             std::uint64_t max_bytes, const std::string& file,
                                             const std::string& element);

} // namespace irad::gltf
