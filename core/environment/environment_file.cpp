// Environment map files: OpenEXR through core/image/image_io.h's read_exr (after a header check of
// our own, so that sizes are refused before any pixel is read), Radiance HDR through stb_image.
// Library failures become fixed phrases of ours: no library text reaches a message.
#include "core/environment/environment_file.h"

#include "core/image/image_io.h"
#include "core/util/error.h"
#include "core/util/number_list.h"

#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <string_view>
#include <system_error>
#include <vector>

// A second static stb_image, Radiance HDR only (core/gltf/decode/image_decode.cpp's copy is PNG and
// JPEG only, STBI_NO_HDR). Static: each copy's functions stay inside its own translation unit.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_HDR
#define STBI_NO_STDIO
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wpedantic"
#include <stb_image.h>
#pragma GCC diagnostic pop

namespace irad {

namespace fs = std::filesystem;

namespace {

enum class MapFormat { Exr, Hdr };

// The thrower of every check here: "PATH: OPTION: MESSAGE".
struct MapError {
  const fs::path& path;
  const std::string& option;
  [[noreturn]] void operator()(const std::string& message) const {
    throw Error(path.string(), option, message);
  }
};

MapFormat format_of(const fs::path& path, const MapError& fail) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".exr") return MapFormat::Exr;
  if (ext == ".hdr" || ext == ".pic") return MapFormat::Hdr;
  const std::string found = ext.empty() ? "no extension" : "unknown extension '" + ext + "'";
  fail(found + " (an environment map is .exr, or Radiance .hdr / .pic)");
}

// The file opened for reading; says why not (missing, a folder, permissions).
std::ifstream open_map(const fs::path& path, const MapError& fail) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) fail("cannot read: it is a folder, not a file");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    fail("cannot read: " + (errno != 0 ? std::generic_category().message(errno)
                                       : std::string("cannot open the file")));
  }
  return in;
}

// The first `limit` bytes of the file (all of it by default).
std::vector<unsigned char> read_bytes(const fs::path& path, const MapError& fail,
                                      std::size_t limit = SIZE_MAX) {
  std::ifstream in = open_map(path, fail);
  std::vector<unsigned char> bytes;
  std::vector<char> chunk(std::size_t{1} << 16);
  while (in && bytes.size() < limit) {
    in.read(chunk.data(),
            static_cast<std::streamsize>(std::min(chunk.size(), limit - bytes.size())));
    const auto* first = reinterpret_cast<const unsigned char*>(chunk.data());
    bytes.insert(bytes.end(), first, first + in.gcount());
  }
  if (in.bad()) fail("cannot read: an I/O error");
  return bytes;
}

bool starts_with(const std::vector<unsigned char>& bytes, std::string_view prefix) {
  return bytes.size() >= prefix.size() &&
         std::memcmp(bytes.data(), prefix.data(), prefix.size()) == 0;
}

// Refuses sizes beyond the limit and maps that are not 2:1; called before any pixel is decoded.
void check_size(int width, int height, const MapError& fail) {
  if (width < 1 || height < 1) fail(fmt::format("{} x {} texels: the map is empty", width, height));
  if (width > kMaxEnvironmentWidth)
    fail(fmt::format("{} x {} texels: wider than the limit of {} texels", width, height,
                     kMaxEnvironmentWidth));
  if (width != 2 * height)
    fail(fmt::format("{} x {} texels: an equirectangular map is twice as wide as high "
                     "(e.g. 2048 x 1024)",
                     width, height));
}

// The first texel (row order) that is not finite or is negative; alpha is set to 1.
void check_texels(Image& image, const MapError& fail) {
  for (int y = 0; y < image.height(); ++y) {
    for (int x = 0; x < image.width(); ++x) {
      glm::vec4& t = image.at(x, y);
      const bool finite = std::isfinite(t.r) && std::isfinite(t.g) && std::isfinite(t.b);
      if (!finite || t.r < 0.0f || t.g < 0.0f || t.b < 0.0f) {
        fail(fmt::format("texel x {}, y {} (row 0 at the top) is ({}, {}, {}): {}", x, y, t.r, t.g,
                         t.b, finite ? "radiance cannot be negative" : "not a finite number"));
      }
      t.a = 1.0f;
    }
  }
}

// OpenEXR: the signature, then the header (size, R, G and B channels), then read_exr's pixels.
Image read_exr_map(const fs::path& path, const MapError& fail) {
  const std::vector<unsigned char> bytes = read_bytes(path, fail, 4);
  if (!starts_with(bytes, "\x76\x2f\x31\x01"))
    fail("not an OpenEXR file (it does not start with the OpenEXR signature)");
  int width = 0, height = 0;
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const long long w = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long h = static_cast<long long>(window.max.y) - window.min.y + 1;
    width = static_cast<int>(std::clamp(w, 0LL, static_cast<long long>(INT_MAX)));
    height = static_cast<int>(std::clamp(h, 0LL, static_cast<long long>(INT_MAX)));
    for (const char* c : {"R", "G", "B"})
      if (file.header().channels().findChannel(c) == nullptr)
        fail(fmt::format("the OpenEXR file has no '{}' channel (an RGB map is needed)", c));
  } catch (const Error&) {
    throw;
  } catch (const std::exception&) {
    fail("the OpenEXR header does not decode (corrupt or truncated file)");
  }
  check_size(width, height, fail);
  try {
    return read_exr(path);
  } catch (const Error&) {
    fail("the OpenEXR pixels do not decode (corrupt or truncated file)");
  }
}

// stb_image's failure reason for an HDR file as one of our phrases.
std::string hdr_reason() {
  const char* reason = stbi_failure_reason();
  const std::string_view r = reason ? reason : "";
  if (r == "not HDR") return "not a Radiance HDR file (no '#?RADIANCE' or '#?RGBE' first line)";
  if (r == "unsupported format") return "an unsupported Radiance HDR format (only 32-bit_rle_rgbe)";
  if (r == "unsupported data layout")
    return "an unsupported Radiance HDR layout (only '-Y HEIGHT +X WIDTH', top row first)";
  if (r == "too large" || r == "outofmem") return "the Radiance HDR file is too large to decode";
  return "the Radiance HDR pixels do not decode (corrupt or truncated file)";
}

// Frees stb_image's pixels.
struct StbFloats {
  float* data = nullptr;
  explicit StbFloats(float* pixels) : data(pixels) {}
  StbFloats(const StbFloats&) = delete;
  StbFloats& operator=(const StbFloats&) = delete;
  ~StbFloats() { stbi_image_free(data); }
};

// Where the pixels of a Radiance HDR file start: after the header's empty line and the
// resolution line that follows it; bytes.size() when the file has no such lines.
std::size_t hdr_pixel_offset(const std::vector<unsigned char>& bytes) {
  static constexpr unsigned char kEnd[] = {'\n', '\n'};
  const auto header_end = std::search(bytes.begin(), bytes.end(), kEnd, kEnd + 2);
  if (header_end == bytes.end()) return bytes.size();
  const auto line_end = std::find(header_end + 2, bytes.end(), '\n');
  return line_end == bytes.end() ? bytes.size()
                                 : static_cast<std::size_t>(line_end - bytes.begin()) + 1;
}

// stb_image reads missing pixel bytes as zeros, without an error, so a truncated file would
// decode as black texels (and a few bytes naming 16384 x 8192 texels would cost 3.5 GiB): the
// pixels must be long enough. Flat scanlines (width < 8 or > 32767, or a first scanline without
// the run-length marker 2, 2) hold exactly 4 bytes per texel; a run-length scanline at least its
// 4-byte marker and, per channel, 2 bytes per run of at most 127 texels.
void check_hdr_length(const std::vector<unsigned char>& bytes, int width, int height,
                      const MapError& fail) {
  const std::size_t offset = hdr_pixel_offset(bytes);
  const std::size_t have = bytes.size() - offset;
  const auto w = static_cast<std::size_t>(width), h = static_cast<std::size_t>(height);
  const bool run_length =
      width >= 8 && width < 32768 && have >= 2 && bytes[offset] == 2 && bytes[offset + 1] == 2;
  const std::size_t need = run_length ? h * (4 + 4 * 2 * ((w + 126) / 127)) : 4 * w * h;
  if (have < need)
    fail(fmt::format("the Radiance HDR file is truncated: {} x {} texels need at least {} bytes "
                     "of pixels, it holds {}",
                     width, height, need, have));
}

// Radiance HDR: the header's size is checked before the pixels are decoded (as RGB floats).
Image read_hdr_map(const fs::path& path, const MapError& fail) {
  constexpr std::size_t kMaxBytes = INT_MAX; // stb_image's limit
  const std::vector<unsigned char> bytes = read_bytes(path, fail, kMaxBytes + 1);
  if (bytes.size() > kMaxBytes) fail("larger than 2 GiB: too large for a Radiance HDR map");
  const int length = static_cast<int>(bytes.size());
  int width = 0, height = 0, channels = 0;
  if (!stbi_is_hdr_from_memory(bytes.data(), length)) {
    fail("not a Radiance HDR file (no '#?RADIANCE' or '#?RGBE' first line)");
  }
  if (!stbi_info_from_memory(bytes.data(), length, &width, &height, &channels)) {
    // stbi_info gives no reason; the loader, refusing the same header, does (before allocating).
    const StbFloats none{
        stbi_loadf_from_memory(bytes.data(), length, &width, &height, &channels, 3)};
    fail(hdr_reason());
  }
  check_size(width, height, fail);
  check_hdr_length(bytes, width, height, fail);
  const StbFloats pixels{
      stbi_loadf_from_memory(bytes.data(), length, &width, &height, &channels, 3)};
  if (pixels.data == nullptr) fail(hdr_reason());
  Image image(width, height);
  for (std::size_t i = 0; i < image.pixels().size(); ++i) {
    const float* rgb = pixels.data + 3 * i;
    image.pixels()[i] = glm::vec4(rgb[0], rgb[1], rgb[2], 1.0f);
  }
  return image;
}

} // namespace

Image read_environment_map(const fs::path& path, const std::string& option) {
  const MapError fail{path, option};
  Image image =
      format_of(path, fail) == MapFormat::Exr ? read_exr_map(path, fail) : read_hdr_map(path, fail);
  check_texels(image, fail);
  return image;
}

glm::vec3 parse_env_color(const std::string& text, const std::string& option) {
  const auto values = parse_number_list(text, 3, 3);
  if (!values)
    throw Error("", option, fmt::format("'{}' is not R,G,B (three finite numbers)", text));
  const glm::vec3 c(static_cast<float>((*values)[0]), static_cast<float>((*values)[1]),
                    static_cast<float>((*values)[2]));
  if (c.r < 0.0f || c.g < 0.0f || c.b < 0.0f)
    throw Error("", option, fmt::format("'{}' is negative: radiance cannot be negative", text));
  if (c == glm::vec3(0.0f))
    throw Error(
        "", option,
        fmt::format("'{}' is black: no light (leave the option out for no environment)", text));
  return c;
}

} // namespace irad
