#pragma once
// Internal to the glTF loader (not part of irad's API): the parsed tinygltf model with the file
// name for messages and the logger, plus index checking shared by the loader's parts.
#include "core/error.h"
#include "core/gltf/loader.h"
#include "core/log.h"

#include <cstddef>
#include <string>
#include <tiny_gltf.h>

namespace irad::gltf {

struct Context {
  const tinygltf::Model& model;
  std::string file; // as given by the caller; the prefix of every message
  Log& log;
  const LoadLimits& limits;

  // Throws Error("FILE", element, message).
  [[noreturn]] void fail(const std::string& element, const std::string& message) const {
    throw Error(file, element, message);
  }
  // Warns with "FILE: message"; identical messages are reported once per logger.
  void warn(const std::string& message) const { log.warn(file + ": " + message); }
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

} // namespace irad::gltf
