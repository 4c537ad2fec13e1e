#pragma once
// Test helper: the Khronos glTF-Validator conformance files (shared/conformance/gltf-validator/
// test/**), each NAME.gltf / NAME.glb beside NAME.report.json, parsed without the loader: the
// JSON, the buffers resolved (GLB BIN chunk for a uri-less buffer 0, base64 data URIs, files
// beside the document) and the report's error-severity messages.
#include "core/gltf/validate/validate.h"
#include "tests/test_paths.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace irad::test {

struct ReportedError {
  std::string code;
  std::string pointer;
};

struct ConformanceFile {
  std::filesystem::path path;
  nlohmann::json root;
  std::vector<std::vector<unsigned char>> storage; // owns the buffers' bytes
  std::vector<gltf::BufferBytes> buffers;
  std::vector<ReportedError> errors; // severity 0 messages of the report
};

inline const std::filesystem::path& conformance_dir() {
  static const std::filesystem::path dir = std::filesystem::path(IRAD_SOURCE_DIR) / ".." /
                                           "shared" / "conformance" / "gltf-validator" / "test";
  return dir;
}

inline std::vector<unsigned char> read_file_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Decodes standard base64 (padding optional); nullopt on any other character.
inline std::optional<std::vector<unsigned char>> decode_base64(const std::string& s) {
  std::vector<unsigned char> out;
  std::uint32_t acc = 0;
  int bits = 0;
  for (char c : s) {
    int v;
    if (c >= 'A' && c <= 'Z')
      v = c - 'A';
    else if (c >= 'a' && c <= 'z')
      v = c - 'a' + 26;
    else if (c >= '0' && c <= '9')
      v = c - '0' + 52;
    else if (c == '+')
      v = 62;
    else if (c == '/')
      v = 63;
    else if (c == '=')
      break;
    else
      return std::nullopt;
    acc = (acc << 6) | static_cast<std::uint32_t>(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((acc >> bits) & 0xFF));
    }
  }
  return out;
}

inline std::uint32_t read_u32(const std::vector<unsigned char>& b, std::size_t at) {
  std::uint32_t v;
  std::memcpy(&v, b.data() + at, 4);
  return v; // little-endian hosts only (x86, arm64)
}

// Splits a GLB into its JSON text and BIN chunk; false when its structure is broken.
inline bool split_glb(const std::vector<unsigned char>& b, std::string& json,
                      std::optional<std::vector<unsigned char>>& bin) {
  // Bytes after the header's total length are ignored (the validator only warns about them).
  if (b.size() < 20 || read_u32(b, 0) != 0x46546C67u) return false;
  const std::size_t total = read_u32(b, 8);
  if (total < 20 || total > b.size()) return false;
  std::size_t at = 12;
  bool first = true;
  while (at + 8 <= total) {
    const std::size_t length = read_u32(b, at);
    const std::uint32_t type = read_u32(b, at + 4);
    if (length > total - at - 8) return false;
    const auto* data = b.data() + at + 8;
    if (first && type != 0x4E4F534Au) return false;
    if (first)
      json.assign(reinterpret_cast<const char*>(data), length);
    else if (type == 0x004E4942u && !bin)
      bin.emplace(data, data + length);
    first = false;
    at += 8 + length;
  }
  return !first && at == total;
}

// Resolves buffer i's bytes into `file`; absent (present == false) when they cannot be had.
inline void resolve_buffer(ConformanceFile& file, const nlohmann::json& buffer, std::size_t i,
                           const std::optional<std::vector<unsigned char>>& bin, bool glb) {
  auto& bytes = file.storage[i];
  gltf::BufferBytes& out = file.buffers[i];
  const nlohmann::json* uri =
      buffer.is_object() && buffer.contains("uri") ? &buffer["uri"] : nullptr;
  if (uri == nullptr) {
    if (i == 0 && glb && bin) {
      bytes = *bin;
      out.present = true;
    } else {
      out.glb_without_bin = i == 0 && glb && !bin;
    }
  } else if (uri->is_string()) {
    const std::string& u = uri->get_ref<const std::string&>();
    if (u.rfind("data:", 0) == 0) {
      const auto comma = u.find(',');
      if (comma != std::string::npos && u.substr(0, comma).find(";base64") != std::string::npos)
        if (auto d = decode_base64(u.substr(comma + 1))) {
          bytes = std::move(*d);
          out.present = true;
        }
    } else if (u.find("://") == std::string::npos) {
      const auto p = file.path.parent_path() / u;
      std::error_code ec;
      if (std::filesystem::is_regular_file(p, ec)) {
        bytes = read_file_bytes(p);
        out.present = true;
      }
    }
  }
  out.data = bytes.data();
  out.size = bytes.size();
}

// Loads one conformance file; nullopt when its JSON does not parse or its GLB is broken.
inline std::optional<ConformanceFile> load_conformance_file(const std::filesystem::path& path) {
  ConformanceFile file;
  file.path = path;
  const auto raw = read_file_bytes(path);
  const bool glb = path.extension() == ".glb";
  std::string text;
  std::optional<std::vector<unsigned char>> bin;
  if (glb) {
    if (!split_glb(raw, text, bin)) return std::nullopt;
  } else {
    text.assign(raw.begin(), raw.end());
  }
  file.root = nlohmann::json::parse(text, nullptr, false);
  if (file.root.is_discarded()) return std::nullopt;
  const nlohmann::json* buffers =
      file.root.is_object() && file.root.contains("buffers") ? &file.root["buffers"] : nullptr;
  const std::size_t n = buffers != nullptr && buffers->is_array() ? buffers->size() : 0;
  file.storage.resize(n);
  file.buffers.resize(n);
  for (std::size_t i = 0; i < n; ++i) resolve_buffer(file, (*buffers)[i], i, bin, glb);
  const auto report =
      nlohmann::json::parse(read_file_bytes(path.string() + ".report.json"), nullptr, false);
  if (report.is_object())
    for (const auto& m : report.value("/issues/messages"_json_pointer, nlohmann::json::array()))
      if (m.value("severity", -1) == 0)
        file.errors.push_back({m.value("code", ""), m.value("pointer", "")});
  return file;
}

// Every conformance document (.gltf and .glb that have a report), sorted.
inline std::vector<std::filesystem::path> conformance_documents() {
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  for (auto it = std::filesystem::recursive_directory_iterator(conformance_dir(), ec);
       it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
    const auto& p = it->path();
    if ((p.extension() == ".gltf" || p.extension() == ".glb") &&
        std::filesystem::exists(p.string() + ".report.json"))
      out.push_back(p);
  }
  std::sort(out.begin(), out.end());
  return out;
}

} // namespace irad::test
