#pragma once
// Internal to the glTF loader (not part of irad's API): the parsed document with its resolved
// buffers, the file name for messages, the logger, the validator's findings, and index checking
// shared by the loader's parts.
#include "core/gltf/issue_book.h"
#include "core/gltf/loader.h"
#include "core/gltf/read/json_read.h"
#include "core/util/error.h"
#include "core/util/log.h"

#include <cstddef>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace irad::gltf {

// The bytes of one buffer, or none (a buffer without data: the validator has said why).
// placeholder: a buffer without uri outside a GLB (valid glTF: its data come from elsewhere,
// e.g. an extension); irad reads its bytes as zeros, with a warning, where they are used.
// The bytes are storage[start, end): a GLB's BIN chunk stays where the file put it, after the
// header and JSON, instead of being moved to the front.
struct BufferData {
  std::vector<unsigned char> storage;
  std::size_t start = 0;
  std::span<const unsigned char> bytes() const {
    return std::span<const unsigned char>(storage).subspan(start);
  }
  bool present = false;
  bool placeholder = false;
  std::uint64_t byte_length = 0;
};

// Buffer views decoded from EXT_meshopt_compression, by view index (filled on first use).
using DecodedViews = std::map<std::size_t, std::vector<unsigned char>>;
// Accessor data decoded from KHR_draco_mesh_compression, tightly packed, by accessor index.
using DecodedAccessors = std::map<std::size_t, std::vector<unsigned char>>;

struct Context {
  const json& root;
  std::string file; // as given by the caller; the prefix of every message
  Log& log;
  const LoadLimits& limits;
  IssueBook& issues;
  const std::vector<BufferData>& buffers;
  DecodedViews& decoded_views;
  DecodedAccessors& decoded_accessors;
  std::filesystem::path folder; // of the scene file: external URIs are relative to it

  // Throws Error("FILE", element, message).
  [[noreturn]] void fail(const std::string& element, const std::string& message) const {
    throw Error(file, element, message);
  }
  // Warns with "FILE: message"; identical messages are reported once per logger.
  void warn(const std::string& message) const { log.warn(file + ": " + message); }

  // Marks the element at JSON pointer `pointer` as used: a validator issue there becomes the
  // error now, before its data are read, or a warning when the loader repairs it or only an
  // extension irad ignores raises it (core/gltf/issue_book.h).
  void use(const std::string& pointer) const { issues.use(pointer, log); }
  // Only the issues at `pointer` itself (an element irad reads part of).
  void use_exact(const std::string& pointer) const { issues.use(pointer, log, true); }
  void use(const char* array, std::size_t i) const { use(pointer_of(array, i)); }

  // The top-level array `name` (empty when absent) and its element i (unchecked: see at()).
  const json& array(const char* name) const { return root_array(root, name); }
  std::size_t count(const char* name) const { return array(name).size(); }
  // Element i of the top-level array `name` after use(); fails at `where` when out of range.
  const json& at(const char* name, std::uint64_t i, const std::string& where,
                 const std::string& what) const;
};

// "array[index]", the glTF JSON path of an element, e.g. element("accessors", 3).
inline std::string element(const char* array, std::size_t index) {
  return std::string(array) + "[" + std::to_string(index) + "]";
}

// Returns index as size_t when 0 <= index < size; otherwise fails at `where` with
// "<what> index I out of range (N available)".
inline std::size_t checked_index(const Context& ctx, long long index, std::size_t size,
                                 const std::string& where, const std::string& what) {
  if (index < 0 || static_cast<unsigned long long>(index) >= size) {
    ctx.fail(where, what + " index " + std::to_string(index) + " out of range (" +
                        std::to_string(size) + " available)");
  }
  return static_cast<std::size_t>(index);
}

// The index property `key` of `object` (at `where`): nullopt when absent; fails when it is not a
// non-negative integer below `size`.
std::optional<std::size_t> optional_index(const Context& ctx, const json& object, const char* key,
                                          std::size_t size, const std::string& where);

inline const json& Context::at(const char* name, std::uint64_t i, const std::string& where,
                               const std::string& what) const {
  const json& a = array(name);
  const std::size_t k = checked_index(
      *this, i > 0x7fffffffffffffffull ? -1 : static_cast<long long>(i), a.size(), where, what);
  use(name, k);
  return a[k];
}

} // namespace irad::gltf
