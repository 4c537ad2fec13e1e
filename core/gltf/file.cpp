#include "core/gltf/file.h"

#include "core/error.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fmt/format.h>
#include <limits>
#include <nlohmann/json.hpp>
#include <stb_image.h>
#include <string_view>
#include <system_error>

namespace irad::gltf {

namespace {

using json = nlohmann::json;
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
      f.bin_length = size;
    } else if (type == kChunkJson || type == kChunkBin) {
      fail(where, "more than one JSON or BIN chunk");
    } else {
      fail(where, "unsupported chunk type " + tag(b.data() + at - 4) +
                      " (only one JSON and one BIN chunk are supported)");
    }
    at += size;
  }
  if (f.json_length == 0) fail("GLB chunks[0]", "missing JSON chunk");
  f.bytes.resize(length);
}

// Parses the JSON text, failing on syntax errors and on nesting deeper than max_depth (tinygltf
// converts extras and extensions recursively: deep nesting would overflow its stack).
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

std::string element(const std::string& array, std::size_t i) {
  return array + "[" + std::to_string(i) + "]";
}

// The checks of the JSON document that tinygltf does not make or words less clearly.
class Checker {
public:
  Checker(const SceneFile& f, const fs::path& folder, const LoadLimits& limits, const Fail& fail)
      : f_(f), folder_(folder), limits_(limits), fail_(fail) {}

  void run(const json& doc) {
    asset(doc);
    indices_and_offsets(doc);
    for_each(doc, "buffers",
             [&](const json& b, const std::string& where, std::size_t i) { buffer(b, where, i); });
    for_each(doc, "images",
             [&](const json& im, const std::string& where, std::size_t) { image(im, where); });
  }

private:
  void asset(const json& doc) {
    const auto a = doc.find("asset");
    if (a == doc.end() || !a->is_object()) fail_("asset", "missing (required)");
    const auto v = a->find("version");
    if (v == a->end() || !v->is_string()) fail_("asset.version", "missing (required)");
    const std::string version = v->get<std::string>();
    if (version.rfind("2.", 0) != 0) {
      fail_("asset.version", "unsupported glTF version '" + version + "'");
    }
  }

  // Calls visit(element, "name[i]", i) for each object of the top-level array `name`.
  template <class Visit>
  void for_each(const json& doc, const char* name, Visit visit) {
    const auto it = doc.find(name);
    if (it == doc.end()) return;
    if (!it->is_array()) fail_(name, "must be an array");
    for (std::size_t i = 0; i < it->size(); ++i) {
      const json& e = (*it)[i];
      const std::string where = element(name, i);
      if (!e.is_object()) fail_(where, "must be an object");
      visit(e, where, i);
    }
  }

  // `key` of `o`, when present, must be an integer >= min. Most fields are ints in tinygltf, which
  // would silently wrap larger values: those must also be <= INT32_MAX (`wide`: size_t fields).
  void non_negative(const json& o, const char* key, const std::string& where, std::int64_t min = 0,
                    bool wide = false) {
    if (!o.is_object()) fail_(where, "must be an object");
    const auto it = o.find(key);
    if (it == o.end()) return;
    const bool ok = it->is_number_unsigned()  ? it->get<std::uint64_t>() >= std::uint64_t(min)
                    : it->is_number_integer() ? it->get<std::int64_t>() >= min
                                              : false;
    if (!ok) fail_(where, fmt::format("{} {} must be an integer >= {}", key, shown(*it), min));
    if (!wide && it->get<std::uint64_t>() > std::uint64_t(std::numeric_limits<int>::max())) {
      fail_(where, fmt::format("{} {} is larger than {}", key, shown(*it),
                               std::numeric_limits<int>::max()));
    }
  }

  // A JSON value for a message: at most 40 characters.
  static std::string shown(const json& value) {
    std::string s = value.dump();
    return s.size() <= 40 ? s : s.substr(0, 40) + "...";
  }

  // Every element of the array `key` of `o` (when present) must be an integer >= 0.
  void non_negative_array(const json& o, const char* key, const std::string& where) {
    const auto it = o.find(key);
    if (it == o.end()) return;
    if (!it->is_array()) fail_(where, std::string(key) + " must be an array");
    for (const json& v : *it) {
      if (!v.is_number_unsigned() ||
          v.get<std::uint64_t>() > std::uint64_t(std::numeric_limits<int>::max())) {
        fail_(where, fmt::format("{} holds {}, not an index >= 0", key, shown(v)));
      }
    }
  }

  void texture_info(const json& m, const char* key, const std::string& where) {
    const auto it = m.find(key);
    if (it == m.end()) return;
    non_negative(*it, "index", where + "." + key);
    non_negative(*it, "texCoord", where + "." + key);
  }

  // Negative indices would read as "absent" and negative offsets as 0 in tinygltf.
  void indices_and_offsets(const json& doc) {
    non_negative(doc, "scene", "scene");
    for_each(doc, "scenes", [&](const json& s, const std::string& where, std::size_t) {
      non_negative_array(s, "nodes", where);
    });
    for_each(doc, "nodes", [&](const json& n, const std::string& where, std::size_t) {
      for (const char* key : {"mesh", "camera", "skin"}) non_negative(n, key, where);
      non_negative_array(n, "children", where);
    });
    for_each(doc, "meshes", [&](const json& m, const std::string& where, std::size_t) {
      const auto p = m.find("primitives");
      if (p == m.end()) return;
      if (!p->is_array()) fail_(where, "primitives must be an array");
      for (std::size_t i = 0; i < p->size(); ++i) {
        const json& prim = (*p)[i];
        const std::string pw = where + element(".primitives", i);
        for (const char* key : {"indices", "material", "mode"}) non_negative(prim, key, pw);
        const auto a = prim.find("attributes");
        if (a == prim.end()) continue;
        if (!a->is_object()) fail_(pw, "attributes must be an object");
        for (const auto& [name, value] : a->items()) {
          if (!value.is_number_unsigned() ||
              value.get<std::uint64_t>() > std::uint64_t(std::numeric_limits<int>::max())) {
            fail_(pw + ".attributes",
                  fmt::format("{} {} must be an accessor index >= 0", name, shown(value)));
          }
        }
      }
    });
    for_each(doc, "materials", [&](const json& m, const std::string& where, std::size_t) {
      texture_info(m, "emissiveTexture", where);
      texture_info(m, "normalTexture", where);
      texture_info(m, "occlusionTexture", where);
      if (const auto pbr = m.find("pbrMetallicRoughness"); pbr != m.end()) {
        texture_info(*pbr, "baseColorTexture", where + ".pbrMetallicRoughness");
        texture_info(*pbr, "metallicRoughnessTexture", where + ".pbrMetallicRoughness");
      }
    });
    for_each(doc, "textures", [&](const json& t, const std::string& where, std::size_t) {
      non_negative(t, "source", where);
      non_negative(t, "sampler", where);
    });
    for_each(doc, "images", [&](const json& im, const std::string& where, std::size_t) {
      non_negative(im, "bufferView", where);
    });
    for_each(doc, "bufferViews", [&](const json& v, const std::string& where, std::size_t) {
      non_negative(v, "buffer", where);
      for (const char* key : {"byteOffset", "byteStride"}) non_negative(v, key, where, 0, true);
      non_negative(v, "byteLength", where, 1, true);
    });
    for_each(doc, "accessors", [&](const json& a, const std::string& where, std::size_t) {
      non_negative(a, "bufferView", where);
      non_negative(a, "componentType", where);
      non_negative(a, "byteOffset", where, 0, true);
      non_negative(a, "count", where, 1, true);
      const auto s = a.find("sparse");
      if (s == a.end()) return;
      non_negative(*s, "count", where + ".sparse", 1);
      for (const char* part : {"indices", "values"}) {
        const auto p = s->find(part);
        if (p == s->end()) continue;
        const std::string pw = where + ".sparse." + part;
        for (const char* key : {"bufferView", "byteOffset", "componentType"})
          non_negative(*p, key, pw);
      }
    });
  }

  // The size of the file an external URI names (percent-decoded as tinygltf does); it must stay
  // inside the scene's folder.
  std::uintmax_t external(const std::string& uri, const std::string& where) {
    std::string path;
    for (std::size_t i = 0; i < uri.size(); ++i) { // tinygltf's urldecode
      if (uri[i] == '+') {
        path += ' ';
      } else if (uri[i] == '%' && i + 2 < uri.size()) {
        auto hex = [](char c) {
          return c >= '0' && c <= '9'   ? c - '0'
                 : c >= 'a' && c <= 'f' ? c - 'a' + 10
                 : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                        : 0;
        };
        path += char(hex(uri[i + 1]) << 4 | hex(uri[i + 2]));
        i += 2;
      } else {
        path += uri[i];
      }
    }
    if (path.empty()) fail_(where, "empty uri");
    if (path.find('\0') != std::string::npos) fail_(where, "uri contains a NUL byte");
    const fs::path relative(path);
    if (relative.is_absolute() || relative.has_root_name() || relative.has_root_directory()) {
      fail_(where, "uri '" + uri +
                       "' is an absolute path (external files must lie in the "
                       "scene's folder)");
    }
    for (const fs::path& part : relative) {
      if (part == "..") {
        fail_(where, "uri '" + uri + "' leaves the scene's folder ('..' is not allowed)");
      }
    }
    const fs::path full = folder_ / relative;
    std::error_code ec;
    const fs::file_status status = fs::status(full, ec);
    if (!fs::exists(status)) fail_(where, "external file '" + uri + "' not found");
    if (!fs::is_regular_file(status)) {
      fail_(where, "external file '" + uri + "' is not a regular file");
    }
    const std::uintmax_t size = fs::file_size(full, ec);
    if (ec) fail_(where, "external file '" + uri + "': " + ec.message());
    if (size > limits_.max_file_bytes) {
      fail_(where, fmt::format("external file '{}' has {} bytes, over the limit of {} "
                               "(--max-file-size)",
                               uri, size, limits_.max_file_bytes));
    }
    return size;
  }

  // Bytes a base64 data URI holds after `header`, failing on anything but base64.
  std::uint64_t base64_bytes(const std::string& uri, std::size_t header, const std::string& where) {
    static constexpr std::string_view kAlphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::size_t n = uri.size();
    std::size_t padding = 0;
    while (n > header && uri[n - 1] == '=' && padding < 2) --n, ++padding;
    for (std::size_t i = header; i < n; ++i) {
      if (kAlphabet.find(uri[i]) == std::string_view::npos) {
        fail_(where, fmt::format("data URI is not valid base64 (character {} of the data)",
                                 i - header + 1));
      }
    }
    const std::size_t chars = n - header;
    if (chars % 4 == 1 || (padding > 0 && (chars + padding) % 4 != 0)) {
      fail_(where, "data URI is not valid base64 (bad length or padding)");
    }
    const std::uint64_t bytes = chars / 4 * 3 + (chars % 4 == 0 ? 0 : chars % 4 - 1);
    if (bytes == 0) fail_(where, "data URI holds no data");
    return bytes;
  }

  // Length of the data URI header among `headers` that `uri` starts with; fails when none does.
  std::size_t data_header(const std::string& uri, std::initializer_list<std::string_view> headers,
                          const std::string& where) {
    for (std::string_view h : headers) {
      if (std::string_view(uri).substr(0, h.size()) == h) return h.size();
    }
    std::string list;
    for (std::string_view h : headers) list += (list.empty() ? "" : " or ") + std::string(h);
    const std::string head = uri.substr(0, std::min<std::size_t>(uri.find(',') + 1, 60));
    fail_(where, "unsupported data URI '" + head + "...' (expected " + list + ")");
  }

  void buffer(const json& b, const std::string& where, std::size_t i) {
    non_negative(b, "byteLength", where, 1, true);
    const auto length_it = b.find("byteLength");
    if (length_it == b.end()) fail_(where, "byteLength is missing");
    const std::uint64_t length = length_it->get<std::uint64_t>();
    const auto uri_it = b.find("uri");
    if (uri_it == b.end()) {
      if (!f_.binary || i != 0) {
        fail_(where, "no uri (only buffers[0] of a GLB may refer to the BIN chunk)");
      }
      if (f_.bin_length == 0) fail_(where, "no uri and the GLB has no BIN chunk");
      if (length > f_.bin_length) {
        fail_(where, fmt::format("byteLength {} exceeds the GLB BIN chunk's {} bytes", length,
                                 f_.bin_length));
      }
      return;
    }
    if (!uri_it->is_string()) fail_(where, "uri must be a string");
    const std::string uri = uri_it->get<std::string>();
    std::uint64_t have = 0;
    std::string what;
    if (uri.rfind("data:", 0) == 0) {
      const std::size_t header = data_header(
          uri, {"data:application/octet-stream;base64,", "data:application/gltf-buffer;base64,"},
          where);
      have = base64_bytes(uri, header, where);
      what = "the data URI holds";
    } else {
      have = external(uri, where);
      what = "'" + uri + "' has";
    }
    if (have < length) {
      fail_(where, fmt::format("{} {} bytes, fewer than byteLength {}", what, have, length));
    }
    if (have > length) {
      fail_(where, fmt::format("{} {} bytes, more than byteLength {} (must be equal)", what, have,
                               length));
    }
  }

  void image(const json& im, const std::string& where) {
    const bool has_uri = im.contains("uri");
    const bool has_view = im.contains("bufferView");
    if (has_uri == has_view) fail_(where, "must have exactly one of uri and bufferView");
    if (!has_uri) return;
    if (!im["uri"].is_string()) fail_(where, "uri must be a string");
    const std::string uri = im["uri"].get<std::string>();
    if (uri.rfind("data:", 0) == 0) {
      base64_bytes(uri,
                   data_header(uri, {"data:image/png;base64,", "data:image/jpeg;base64,"}, where),
                   where);
    } else {
      external(uri, where);
    }
  }

  const SceneFile& f_;
  const fs::path& folder_;
  const LoadLimits& limits_;
  const Fail& fail_;
};

} // namespace

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
  std::array<unsigned char, 65536> block;
  std::size_t n = 0;
  while ((n = std::fread(block.data(), 1, block.size(), in)) > 0) {
    if (bytes.size() + n > max_bytes) {
      std::fclose(in);
      throw Error(
          file, element,
          fmt::format("file larger than the limit of {} bytes (--max-file-size)", max_bytes));
    }
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
  // tinygltf takes sizes as unsigned int.
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
  const json doc = parse_json(f, limits.max_json_depth, fail);
  Checker(f, path.parent_path(), limits, fail).run(doc);
  return f;
}

void check_image_bytes(const std::string& file, const std::string& element,
                       const unsigned char* bytes, std::size_t size, const LoadLimits& limits,
                       std::uint64_t& texels) {
  static constexpr unsigned char kPng[] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  static constexpr unsigned char kJpeg[] = {0xFF, 0xD8, 0xFF};
  const bool png = size >= sizeof kPng && std::memcmp(bytes, kPng, sizeof kPng) == 0;
  const bool jpeg = size >= sizeof kJpeg && std::memcmp(bytes, kJpeg, sizeof kJpeg) == 0;
  if (!png && !jpeg) throw Error(file, element, "not a PNG or JPEG image");
  // stb_image copies a first IDAT chunk of length 0 to a null pointer (undefined behaviour,
  // found by the fuzzer): such PNGs are refused. Chunks: length (big-endian), type, data, CRC.
  for (std::size_t at = sizeof kPng; png && size - at >= 8;) {
    const std::uint32_t length = std::uint32_t(bytes[at]) << 24 |
                                 std::uint32_t(bytes[at + 1]) << 16 |
                                 std::uint32_t(bytes[at + 2]) << 8 | std::uint32_t(bytes[at + 3]);
    if (length == 0 && std::memcmp(bytes + at + 4, "IDAT", 4) == 0) {
      throw Error(file, element, "PNG with an empty IDAT chunk (not supported)");
    }
    if (length > size - at - 8) break; // truncated: left to the decoder
    at += 8 + std::size_t(length) + 4;
    if (at > size) break;
  }
  int w = 0, h = 0, channels = 0;
  if (size > std::size_t(std::numeric_limits<int>::max()) ||
      !stbi_info_from_memory(bytes, int(size), &w, &h, &channels)) {
    throw Error(file, element,
                std::string("cannot decode the ") + (png ? "PNG" : "JPEG") + " image header");
  }
  if (w < 1 || h < 1 || w > limits.max_texture_size || h > limits.max_texture_size) {
    throw Error(file, element,
                fmt::format("{}x{} texels: over the limit of {} per side (--max-texture-size)", w,
                            h, limits.max_texture_size));
  }
  texels += std::uint64_t(w) * std::uint64_t(h);
  if (texels > limits.max_texture_texels) {
    throw Error(file, element,
                fmt::format("the images hold {} texels, over the limit of {} for all images "
                            "together",
                            texels, limits.max_texture_texels));
  }
}

} // namespace irad::gltf
