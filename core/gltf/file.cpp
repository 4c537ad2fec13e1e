#include "core/gltf/file.h"

#include "core/util/error.h"
#include "core/util/freed_memory.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fmt/format.h>
#include <limits>
#include <string_view>
#include <sys/stat.h>
#include <system_error>

namespace irad::gltf {

namespace {

namespace fs = std::filesystem;

constexpr std::uint32_t kGlbMagic = 0x46546C67; // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;
constexpr std::uint32_t kChunkBin = 0x004E4942;

std::uint32_t le32(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
         std::uint32_t(p[3]) << 24;
}

// Printable rendering of a 4-byte tag, e.g. 'glTX' or 0x00ff1234.
std::string tag(const unsigned char* p) {
  bool printable = true;
  for (int i = 0; i < 4; ++i) printable = printable && p[i] >= 0x20 && p[i] < 0x7f;
  if (printable) return fmt::format("'{}'", std::string_view(reinterpret_cast<const char*>(p), 4));
  return fmt::format("0x{:08x}", le32(p));
}

// Error() for this file.
class Fail {
public:
  explicit Fail(const std::string& file) : file_(file) {}
  [[noreturn]] void operator()(const std::string& element, const std::string& message) const {
    throw Error(file_, element, message);
  }
  const std::string& file() const { return file_; }

private:
  const std::string& file_;
};

// GLB layout (glTF 2.0 section 4.4): a 12-byte header (magic, version 2, length), then chunks of
// (length, type, payload): JSON first, then an optional BIN. Chunks of other types are skipped.
void split_glb(SceneFile& f, const Fail& fail) {
  const auto& b = f.bytes;
  if (b.size() < 12) {
    fail("GLB header", fmt::format("truncated: {} bytes, 12 needed", b.size()));
  }
  if (le32(b.data()) != kGlbMagic) {
    fail("GLB header", "bad magic " + tag(b.data()) + " (expected 'glTF')");
  }
  if (const std::uint32_t version = le32(b.data() + 4); version != 2) {
    fail("GLB header", fmt::format("unsupported GLB version {} (must be 2)", version));
  }
  const std::uint32_t length = le32(b.data() + 8);
  if (length > b.size()) {
    fail("GLB header",
         fmt::format("length {} exceeds the file's {} bytes (truncated)", length, b.size()));
  }
  std::size_t at = 12;
  for (int chunk = 0; at < length; ++chunk) {
    const std::string where = fmt::format("GLB chunks[{}]", chunk);
    if (length - at < 8) {
      fail(where, fmt::format("truncated chunk header: {} bytes left, 8 needed", length - at));
    }
    const std::uint32_t size = le32(b.data() + at);
    const std::uint32_t type = le32(b.data() + at + 4);
    at += 8;
    if (size > length - at) {
      fail(where,
           fmt::format("chunk length {} exceeds the {} bytes left in the file", size, length - at));
    }
    if (chunk == 0 && type != kChunkJson) {
      fail(where, "the first chunk must be JSON, got type " + tag(b.data() + at - 4));
    }
    if (size % 4 != 0) {
      fail(where, fmt::format("chunk length {} is not a multiple of 4", size));
    }
    if (chunk == 0) {
      if (size == 0) fail(where, "empty JSON chunk");
      f.json_offset = at;
      f.json_length = size;
    } else if (chunk == 1 && type == kChunkBin) {
      f.bin_offset = at;
      f.bin_length = size;
    } else if (type == kChunkJson || type == kChunkBin) {
      fail(where, "more than one JSON or BIN chunk");
    } // chunks of other types are skipped (glTF 2.0 section 4.4.3.1)
    at += size;
  }
  if (f.json_length == 0) fail("GLB chunks[0]", "missing JSON chunk");
  f.bytes.resize(length);
}

// Parses the JSON text, failing on syntax errors and on nesting deeper than max_depth (a JSON
// value's copy and comparison recurse into it: deep nesting would overflow the stack).
json parse_json(const SceneFile& f, int max_depth, const Fail& fail) {
  const auto* text = reinterpret_cast<const char*>(f.bytes.data() + f.json_offset);
  const json::parser_callback_t limit_depth = [&](int depth, json::parse_event_t, json&) {
    if (depth > max_depth) {
      fail("JSON", fmt::format("nested deeper than the limit of {} levels", max_depth));
    }
    return true;
  };
  json doc;
  try {
    doc = json::parse(text, text + f.json_length, limit_depth);
  } catch (const json::exception& e) {
    std::string what = e.what();
    if (const auto end = what.find("] ");
        what.rfind("[json.exception.", 0) == 0 && end != what.npos)
      what = what.substr(end + 2);
    fail("JSON", "not valid JSON: " + what);
  }
  if (!doc.is_object()) fail("JSON", "the top level is not an object");
  return doc;
}

// asset.version must be "2.x" (a major version irad reads); minVersion, when given, at most 2.0.
void check_asset(const json& doc, const Fail& fail) {
  const json* asset = member(doc, "asset");
  if (!asset || !asset->is_object()) fail("asset", "missing (required)");
  const json* version = member(*asset, "version");
  if (!version || !version->is_string()) fail("asset.version", "missing (required)");
  const std::string v = version->get<std::string>();
  if (v.rfind("2.", 0) != 0) fail("asset.version", "unsupported glTF version '" + v + "'");
  if (const json* min = member(*asset, "minVersion"); min && min->is_string()) {
    const std::string m = min->get<std::string>();
    if (m != "2.0") fail("asset.minVersion", "unsupported glTF minVersion '" + m + "'");
  }
}

// RFC 3986 percent-decoding of a relative URI reference.
std::string percent_decoded(const std::string& uri) {
  auto hex = [](char c) {
    return c >= '0' && c <= '9'   ? c - '0'
           : c >= 'a' && c <= 'f' ? c - 'a' + 10
           : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                  : -1;
  };
  std::string path;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      path += char(hex(uri[i + 1]) << 4 | hex(uri[i + 2]));
      i += 2;
    } else {
      path += uri[i];
    }
  }
  return path;
}

// The file an external URI names; it must stay inside the scene's folder.
std::vector<unsigned char> external_bytes(const std::string& uri, const fs::path& folder,
                                          const LoadLimits& limits, const Fail& fail,
                                          const std::string& where) {
  if (uri.find("://") != std::string::npos) {
    fail(where, "uri '" + uri + "' is not a relative path (irad reads no network resources)");
  }
  const std::string path = percent_decoded(uri);
  if (path.empty()) fail(where, "empty uri");
  if (path.find('\0') != std::string::npos) fail(where, "uri contains a NUL byte");
  const fs::path relative(path);
  if (relative.is_absolute() || relative.has_root_name() || relative.has_root_directory()) {
    fail(where, "uri '" + uri +
                    "' is an absolute path (external files must lie in the scene's "
                    "folder)");
  }
  for (const fs::path& part : relative) {
    if (part == "..") fail(where, "uri '" + uri + "' leaves the scene's folder ('..')");
  }
  const fs::path full = folder / relative;
  std::error_code ec;
  const fs::file_status status = fs::status(full, ec);
  if (!fs::exists(status)) fail(where, "external file '" + uri + "' not found");
  if (!fs::is_regular_file(status)) fail(where, "external file '" + uri + "' is not a file");
  return read_file_limited(full, limits.max_file_bytes, fail.file(), where);
}

// Decodes base64 text (RFC 4648, padding optional), failing on any other character.
std::vector<unsigned char> base64_decoded(std::string_view text, const Fail& fail,
                                          const std::string& where) {
  static constexpr std::string_view kAlphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::size_t n = text.size();
  std::size_t padding = 0;
  while (n > 0 && text[n - 1] == '=' && padding < 2) --n, ++padding;
  if (n % 4 == 1 || (padding > 0 && (n + padding) % 4 != 0)) {
    fail(where, "data URI is not valid base64 (bad length or padding)");
  }
  std::vector<unsigned char> out;
  out.reserve(n / 4 * 3 + 2);
  std::uint32_t acc = 0;
  int bits = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t v = kAlphabet.find(text[i]);
    if (v == std::string_view::npos) {
      fail(where, fmt::format("data URI is not valid base64 (character {} of the data)", i + 1));
    }
    acc = (acc << 6) | std::uint32_t(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((acc >> bits) & 0xFFu));
    }
  }
  return out;
}

} // namespace

std::vector<unsigned char> uri_bytes(const std::string& uri,
                                     std::initializer_list<std::string_view> media,
                                     const fs::path& folder, const LoadLimits& limits,
                                     const std::string& file, const std::string& where) {
  const Fail fail(file);
  if (uri.rfind("data:", 0) != 0) return external_bytes(uri, folder, limits, fail, where);
  const std::size_t comma = uri.find(',');
  const std::string_view header = std::string_view(uri).substr(0, comma);
  bool known = false;
  for (std::string_view m : media) {
    known = known || header == "data:" + std::string(m) + ";base64";
  }
  if (comma == std::string::npos || !known) {
    std::string list;
    for (std::string_view m : media) list += (list.empty() ? "" : ", ") + std::string(m);
    fail(where, "unsupported data URI '" + std::string(header.substr(0, 60)) +
                    "' (expected base64 data of type " + list + ")");
  }
  if (uri.size() - comma - 1 > limits.max_file_bytes / 3 * 4 + 4) {
    fail(where, fmt::format("data URI larger than the limit of {} bytes (--max-file-size)",
                            limits.max_file_bytes));
  }
  std::vector<unsigned char> bytes =
      base64_decoded(std::string_view(uri).substr(comma + 1), fail, where);
  if (bytes.empty()) fail(where, "data URI holds no data");
  return bytes;
}

std::vector<unsigned char> read_file_limited(const std::filesystem::path& path,
                                             std::uint64_t max_bytes, const std::string& file,
                                             const std::string& element) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw Error(file, element, "cannot open file: is a directory");
  std::FILE* in = std::fopen(path.c_str(), "rb");
  if (in == nullptr) {
    throw Error(file, element, "cannot open file: " + std::generic_category().message(errno));
  }
  std::vector<unsigned char> bytes;
  auto too_large = [&] {
    std::fclose(in);
    return Error(
        file, element,
        fmt::format("file larger than the limit of {} bytes (--max-file-size)", max_bytes));
  };
  // Room for the whole file at once (a file that grows meanwhile is read to its end all the
  // same): growing by doubling would touch and copy about twice its size.
  if (struct stat st{}; fstat(fileno(in), &st) == 0 && st.st_size > 0) {
    if (static_cast<std::uint64_t>(st.st_size) > max_bytes) throw too_large();
    reserve_huge(bytes, static_cast<std::size_t>(st.st_size));
  }
  std::array<unsigned char, 65536> block;
  std::size_t n = 0;
  while ((n = std::fread(block.data(), 1, block.size(), in)) > 0) {
    if (bytes.size() + n > max_bytes) throw too_large();
    bytes.insert(bytes.end(), block.begin(), block.begin() + std::ptrdiff_t(n));
  }
  const bool failed = std::ferror(in) != 0;
  const int error = errno;
  std::fclose(in);
  if (failed) {
    throw Error(file, element, "cannot read file: " + std::generic_category().message(error));
  }
  return bytes;
}

SceneFile read_scene_file(const std::filesystem::path& path, const std::string& file,
                          const LoadLimits& limits) {
  const Fail fail(file);
  SceneFile f;
  const std::uint64_t max_bytes = std::min<std::uint64_t>(limits.max_file_bytes, 0xFFFFFFFFu);
  f.bytes = read_file_limited(path, max_bytes, file, "");
  if (f.bytes.empty()) fail("", "empty file");
  std::string extension = path.extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  f.binary = (f.bytes.size() >= 4 && le32(f.bytes.data()) == kGlbMagic) || extension == ".glb";
  if (f.binary) {
    split_glb(f, fail);
  } else {
    f.json_length = f.bytes.size();
  }
  f.root = parse_json(f, limits.max_json_depth, fail);
  check_asset(f.root, fail);
  return f;
}

std::vector<BufferData> resolve_buffers(SceneFile& f, const fs::path& folder,
                                        const LoadLimits& limits, IssueBook& issues) {
  const json& buffers = root_array(f.root, "buffers");
  std::vector<BufferData> out(buffers.size());
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    const json& b = buffers[i];
    const std::string pointer = pointer_of("buffers", i);
    const json* uri = member(b, "uri");
    if (!uri) {
      if (f.binary && i == 0 && f.bin_length > 0) {
        // The file's bytes become the buffer's, the BIN chunk where it lies (no copy, no move).
        out[i].storage = std::move(f.bytes);
        out[i].storage.resize(f.bin_offset + f.bin_length);
        out[i].start = f.bin_offset;
        out[i].present = true;
      } else if (!(f.binary && i == 0)) { // (a GLB without BIN: the validator's error)
        out[i].placeholder = true;
        out[i].byte_length = index_member(b, "byteLength").value_or(0);
      }
      continue;
    }
    if (!uri->is_string()) continue; // the validator's TYPE_MISMATCH
    try {
      out[i].storage = uri_bytes(uri->get<std::string>(),
                                 {"application/octet-stream", "application/gltf-buffer"}, folder,
                                 limits, std::string(), pointer);
      out[i].present = true;
      const std::uint64_t length = index_member(b, "byteLength").value_or(0);
      if (out[i].storage.size() != length) {
        issues.add({pointer, "BUFFER_BYTE_LENGTH_MISMATCH",
                    fmt::format("its data hold {} bytes, byteLength says {}", out[i].storage.size(),
                                length)});
      }
    } catch (const Error& e) {
      // Error's text is "POINTER: message" (the file is added by the book).
      std::string what = e.what();
      if (what.rfind(pointer + ": ", 0) == 0) what = what.substr(pointer.size() + 2);
      issues.add({pointer, "IO_ERROR", what});
    }
  }
  return out;
}

} // namespace irad::gltf
