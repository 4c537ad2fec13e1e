// The URI rules of buffers and images: URI syntax, data URIs (RFC 2397: media type, parameters,
// base64 payload), their media types, and the image format a data URI's bytes declare.
#include "core/gltf/validate/validate_schema_internal.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <initializer_list>

namespace irad::gltf::schema {
namespace {

struct DataUri {
  std::string media; // lower case; "" when none is given
  std::vector<unsigned char> bytes;
};

enum class Parsed : std::uint8_t { NotData, Data, Invalid };

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

int base64_digit(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+' || c == '-') return 62;
  if (c == '/' || c == '_') return 63;
  return -1;
}

// Standard or URL-safe base64, padding optional; false on any other character or a dangling
// sextet.
bool decode_base64(std::string_view s, std::vector<unsigned char>& out) {
  while (!s.empty() && s.back() == '=') s.remove_suffix(1);
  if (s.size() % 4 == 1) return false;
  unsigned bits = 0;
  int count = 0;
  for (char c : s) {
    const int d = base64_digit(c);
    if (d < 0) return false;
    bits = (bits << 6) | static_cast<unsigned>(d);
    count += 6;
    if (count >= 8) {
      count -= 8;
      out.push_back(static_cast<unsigned char>((bits >> count) & 0xFFu));
    }
  }
  return true;
}

// data:[<media type>][;name=value]*[;base64],<data>
Parsed parse_data_uri(std::string_view uri, DataUri& out) {
  if (uri.size() < 5 || lower(uri.substr(0, 5)) != "data:") return Parsed::NotData;
  uri.remove_prefix(5);
  const std::size_t comma = uri.find(',');
  if (comma == std::string_view::npos) return Parsed::Invalid;
  std::string_view header = uri.substr(0, comma);
  const std::size_t semi = std::min(header.find(';'), header.size());
  out.media = lower(header.substr(0, semi));
  header.remove_prefix(semi);
  bool base64 = false;
  while (!header.empty()) {
    header.remove_prefix(1);
    const std::size_t end = std::min(header.find(';'), header.size());
    const std::string_view part = header.substr(0, end);
    header.remove_prefix(end);
    if (part == "base64" && header.empty())
      base64 = true;
    else if (part.find('=') == std::string_view::npos || part.front() == '=')
      return Parsed::Invalid;
  }
  const std::string_view data = uri.substr(comma + 1);
  if (!base64) {
    out.bytes.assign(data.begin(), data.end());
    return Parsed::Data;
  }
  return decode_base64(data, out.bytes) ? Parsed::Data : Parsed::Invalid;
}

// A URI reference's scheme, when it has one, must be ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ).
bool uri_syntax_ok(std::string_view uri) {
  const std::size_t colon = uri.find(':');
  if (colon == std::string_view::npos || uri.find_first_of("/?#") < colon) return true;
  const std::string_view scheme = uri.substr(0, colon);
  if (scheme.empty() || !std::isalpha(static_cast<unsigned char>(scheme.front()))) return false;
  return std::all_of(scheme.begin(), scheme.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.';
  });
}

bool starts_with(const std::vector<unsigned char>& b, std::size_t at, std::string_view magic) {
  if (b.size() < at + magic.size()) return false;
  return std::equal(magic.begin(), magic.end(), b.begin() + static_cast<std::ptrdiff_t>(at),
                    [](char m, unsigned char c) { return static_cast<unsigned char>(m) == c; });
}

// The image format the bytes start with; "" when none irad knows.
std::string_view sniff(const std::vector<unsigned char>& b) {
  if (starts_with(b, 0, "\x89PNG\r\n\x1a\n")) return "image/png";
  if (starts_with(b, 0, "\xff\xd8\xff")) return "image/jpeg";
  if (starts_with(b, 0, "RIFF") && starts_with(b, 8, "WEBP")) return "image/webp";
  if (starts_with(b, 0, "\xabKTX 20\xbb\r\n\x1a\n")) return "image/ktx2";
  return "";
}

const std::string* string_member(const nlohmann::json& obj, std::string_view key) {
  const nlohmann::json* v = member(obj, key);
  return v != nullptr && v->is_string() ? &v->get_ref<const std::string&>() : nullptr;
}

void invalid_uri(const std::string& ptr, std::string_view why, Ctx& ctx) {
  ctx.add(ptr, "INVALID_URI", "not a valid URI: " + std::string(why));
}

// The MIME type an image is known by: its mimeType, its data URI's, its bytes', its file name's.
std::string image_type(const nlohmann::json& obj, const DataUri* data, std::string_view uri) {
  if (const std::string* mime = string_member(obj, "mimeType")) return *mime;
  if (data != nullptr) return data->media.empty() ? std::string(sniff(data->bytes)) : data->media;
  const std::string name = lower(uri.substr(0, uri.find_first_of("?#")));
  if (name.ends_with(".webp")) return "image/webp";
  if (name.ends_with(".ktx2")) return "image/ktx2";
  return "";
}

// The MIME type the document declares for image `index`: its mimeType, else its data URI's
// media type; "" when it declares none (or there is no such image).
std::string declared_type(const nlohmann::json& root, const nlohmann::json& index) {
  const nlohmann::json* images = member(root, "images");
  if (!index.is_number_unsigned() || images == nullptr || !images->is_array() ||
      index.get<std::uint64_t>() >= images->size())
    return "";
  const nlohmann::json& image = (*images)[index.get<std::size_t>()];
  if (const std::string* mime = string_member(image, "mimeType")) return *mime;
  DataUri data;
  const std::string* uri = string_member(image, "uri");
  return uri != nullptr && parse_data_uri(*uri, data) == Parsed::Data ? data.media : "";
}

// `holder`'s source must be an image of one of `allowed` types.
void check_source(const nlohmann::json& holder, std::initializer_list<std::string_view> allowed,
                  const std::string& ptr, Ctx& ctx) {
  const nlohmann::json* source = member(holder, "source");
  if (source == nullptr) return;
  const std::string type = declared_type(ctx.root, *source);
  if (!type.empty() && std::find(allowed.begin(), allowed.end(), type) == allowed.end())
    ctx.add(child(ptr, "source"), "TEXTURE_INVALID_IMAGE_MIME_TYPE",
            "an image of type " + type + " cannot be this texture's source");
}

} // namespace

void rule_texture(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx) {
  check_source(obj, {"image/jpeg", "image/png"}, ptr, ctx);
  const nlohmann::json* ext = member(obj, "extensions");
  if (ext == nullptr) return;
  const std::string at = child(ptr, "extensions");
  if (const nlohmann::json* webp = member(*ext, "EXT_texture_webp");
      webp != nullptr && ctx.used("EXT_texture_webp"))
    check_source(*webp, {"image/webp"}, child(at, "EXT_texture_webp"), ctx);
  if (const nlohmann::json* basisu = member(*ext, "KHR_texture_basisu");
      basisu != nullptr && ctx.used("KHR_texture_basisu"))
    check_source(*basisu, {"image/ktx2"}, child(at, "KHR_texture_basisu"), ctx);
}

void rule_buffer(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx) {
  const std::string* uri = string_member(obj, "uri");
  if (uri == nullptr) return;
  const std::string at = child(ptr, "uri");
  DataUri data;
  const Parsed parsed = parse_data_uri(*uri, data);
  if (parsed == Parsed::Invalid) return invalid_uri(at, "malformed data URI", ctx);
  if (parsed == Parsed::NotData) {
    if (!uri_syntax_ok(*uri)) invalid_uri(at, "malformed scheme", ctx);
    return;
  }
  if (data.media != "application/octet-stream" && data.media != "application/gltf-buffer")
    ctx.add(at, "BUFFER_DATA_URI_MIME_TYPE_INVALID",
            "a buffer's data URI must be application/octet-stream or application/gltf-buffer");
}

void rule_image(const nlohmann::json& obj, const std::string& ptr, Ctx& ctx) {
  const bool has_uri = member(obj, "uri") != nullptr;
  const bool has_view = member(obj, "bufferView") != nullptr;
  if (has_uri == has_view)
    ctx.add(ptr, "ONE_OF_MISMATCH", "exactly one of 'uri' and 'bufferView' must be defined");
  if (has_view && member(obj, "mimeType") == nullptr)
    ctx.add(child(ptr, "bufferView"), "UNSATISFIED_DEPENDENCY", "needs 'mimeType' to be defined");
  const std::string* uri = string_member(obj, "uri");
  const std::string at = child(ptr, "uri");
  DataUri data;
  const Parsed parsed = uri != nullptr ? parse_data_uri(*uri, data) : Parsed::NotData;
  if (parsed == Parsed::Invalid) invalid_uri(at, "malformed data URI", ctx);
  if (parsed == Parsed::NotData && uri != nullptr && !uri_syntax_ok(*uri))
    invalid_uri(at, "malformed scheme", ctx);
  if (parsed == Parsed::Data) {
    const std::string_view found = sniff(data.bytes);
    const std::string* mime = string_member(obj, "mimeType");
    if (!found.empty() && data.media.starts_with("image/") && data.media != found)
      invalid_uri(at, "its media type is not the format of its data", ctx);
    else if (!found.empty() && mime != nullptr && *mime != found)
      ctx.add(at, "IMAGE_MIME_TYPE_INVALID",
              "the data is " + std::string(found) + ", not the declared " + *mime);
  }
  const std::string type =
      image_type(obj, parsed == Parsed::Data ? &data : nullptr, uri != nullptr ? *uri : "");
  if ((type == "image/webp" && !ctx.used("EXT_texture_webp")) ||
      (type == "image/ktx2" && !ctx.used("KHR_texture_basisu")))
    ctx.add(ptr, "IMAGE_NON_ENABLED_MIME_TYPE", "MIME type " + type + " needs its extension");
}

} // namespace irad::gltf::schema
