// PNG and JPEG through stb_image (compiled here, static, PNG and JPEG only), WebP through libwebp.
#include "core/gltf/decode/image_decode.h"

#include <cstring>
#include <limits>
#include <string_view>

#include <fmt/format.h>

// stb_image for PNG and JPEG (core/environment/environment_file.cpp compiles its own, HDR only).
// Static, so that it cannot clash with another copy (Debian's libstb, the other one, the fuzz
// build's).
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#define STBI_NO_HDR
#define STBI_NO_LINEAR
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

#include <webp/decode.h>

namespace irad::gltf {

namespace {

constexpr unsigned char kPngSignature[] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
constexpr unsigned char kJpegSignature[] = {0xFF, 0xD8, 0xFF};

bool starts_with(const unsigned char* bytes, std::size_t size, const unsigned char* prefix,
                 std::size_t length) {
  return size >= length && std::memcmp(bytes, prefix, length) == 0;
}

// "the PNG does not decode (corrupt data)".
ImageError not_decoding(ImageFormat format, std::string_view why) {
  return ImageError(fmt::format("the {} does not decode ({})", image_format_name(format), why));
}

// stb_image's failure reason (its short, non-user strings) as one of a few fixed phrases.
std::string_view stb_reason() {
  const char* reason = stbi_failure_reason();
  const std::string_view r = reason ? reason : "";
  if (r == "outofmem") return "out of memory";
  if (r == "too large") return "too large to decode";
  if (r == "1/2/4/8/16-bit only" || r == "only 8-bit" || r == "no header height") {
    return "an unsupported variant";
  }
  return "corrupt data";
}

// Refuses sizes beyond the limits; called with the header's size, before any pixel is decoded.
void check_size(ImageFormat format, int width, int height, const ImageLimits& limits) {
  if (width < 1 || height < 1) throw not_decoding(format, "no texels");
  if (width > limits.max_side || height > limits.max_side) {
    throw ImageError(
        fmt::format("{} x {} texels exceed --max-texture-size {}", width, height, limits.max_side));
  }
  const std::uint64_t texels = std::uint64_t(width) * std::uint64_t(height);
  if (texels > limits.max_texels) {
    throw ImageError(fmt::format("{} x {} texels exceed the limit of {} texels per image", width,
                                 height, limits.max_texels));
  }
}

// Walks a PNG's chunks (length, big-endian; type; data; CRC) up to the first IDAT. Refuses a
// first IDAT chunk of length 0, which stb_image copies to a null pointer (undefined behaviour,
// found by the fuzzer). Returns whether a grey or RGB PNG has a tRNS colour key, which
// stb_image expands to an alpha channel that stbi_info does not count.
bool png_has_colour_key(const unsigned char* bytes, std::size_t size) {
  constexpr std::size_t kColourType = sizeof kPngSignature + 8 + 9; // in IHDR's data
  const bool paletted = size > kColourType && bytes[kColourType] == 3;
  for (std::size_t at = sizeof kPngSignature; size - at >= 8;) {
    const std::uint32_t length = std::uint32_t(bytes[at]) << 24 |
                                 std::uint32_t(bytes[at + 1]) << 16 |
                                 std::uint32_t(bytes[at + 2]) << 8 | std::uint32_t(bytes[at + 3]);
    const unsigned char* type = bytes + at + 4;
    if (std::memcmp(type, "IDAT", 4) == 0) {
      if (length == 0) throw ImageError("PNG with an empty IDAT chunk (not supported)");
      return false;
    }
    if (std::memcmp(type, "tRNS", 4) == 0) return !paletted;
    if (length > size - at - 8) return false; // truncated: left to the decoder
    at += 8 + std::size_t(length) + 4;
    if (at > size) return false;
  }
  return false;
}

// Frees stb_image's pixels.
struct StbPixels {
  void* data;
  ~StbPixels() { stbi_image_free(data); }
};

DecodedImage decode_stb(ImageFormat format, const unsigned char* bytes, std::size_t size,
                        const ImageLimits& limits) {
  if (size > std::size_t(std::numeric_limits<int>::max())) {
    throw not_decoding(format, "too large to decode");
  }
  const bool colour_key = format == ImageFormat::Png && png_has_colour_key(bytes, size);
  const int length = int(size);
  DecodedImage image;
  if (!stbi_info_from_memory(bytes, length, &image.width, &image.height, &image.channels)) {
    throw not_decoding(format, stb_reason());
  }
  check_size(format, image.width, image.height, limits);
  if (colour_key && (image.channels == 1 || image.channels == 3)) ++image.channels;
  image.bits = format == ImageFormat::Png && stbi_is_16_bit_from_memory(bytes, length) ? 16 : 8;
  int w = 0, h = 0, channels = 0;
  const StbPixels pixels{image.bits == 16 ? static_cast<void*>(stbi_load_16_from_memory(
                                                bytes, length, &w, &h, &channels, image.channels))
                                          : static_cast<void*>(stbi_load_from_memory(
                                                bytes, length, &w, &h, &channels, image.channels))};
  if (!pixels.data) throw not_decoding(format, stb_reason());
  // `channels` is the file's count (before the colour key); the pixels have image.channels.
  if (w != image.width || h != image.height || image.channels < 1 || image.channels > 4) {
    throw not_decoding(format, "inconsistent header");
  }
  const std::size_t bytes_out =
      std::size_t(w) * std::size_t(h) * std::size_t(image.channels) * std::size_t(image.bits / 8);
  const auto* first = static_cast<const unsigned char*>(pixels.data);
  image.pixels.assign(first, first + bytes_out);
  return image;
}

DecodedImage decode_webp(const unsigned char* bytes, std::size_t size, const ImageLimits& limits) {
  constexpr ImageFormat format = ImageFormat::Webp;
  WebPBitstreamFeatures features;
  if (WebPGetFeatures(bytes, size, &features) != VP8_STATUS_OK) {
    throw not_decoding(format, "corrupt data");
  }
  if (features.has_animation) throw not_decoding(format, "an unsupported variant (animated)");
  check_size(format, features.width, features.height, limits);
  DecodedImage image;
  image.width = features.width;
  image.height = features.height;
  image.channels = features.has_alpha ? 4 : 3;
  const std::size_t stride = std::size_t(image.width) * std::size_t(image.channels);
  image.pixels.resize(stride * std::size_t(image.height));
  const int row_bytes = int(stride); // <= 4 * max_side, well within int
  const std::uint8_t* done =
      features.has_alpha
          ? WebPDecodeRGBAInto(bytes, size, image.pixels.data(), image.pixels.size(), row_bytes)
          : WebPDecodeRGBInto(bytes, size, image.pixels.data(), image.pixels.size(), row_bytes);
  if (!done) throw not_decoding(format, "corrupt data");
  return image;
}

} // namespace

ImageFormat sniff_image(const unsigned char* bytes, std::size_t size) {
  if (!bytes) return ImageFormat::Unknown;
  if (starts_with(bytes, size, kPngSignature, sizeof kPngSignature)) return ImageFormat::Png;
  if (starts_with(bytes, size, kJpegSignature, sizeof kJpegSignature)) return ImageFormat::Jpeg;
  if (size >= 12 && std::memcmp(bytes, "RIFF", 4) == 0 && std::memcmp(bytes + 8, "WEBP", 4) == 0) {
    return ImageFormat::Webp;
  }
  return ImageFormat::Unknown;
}

const char* image_format_name(ImageFormat format) {
  switch (format) {
  case ImageFormat::Png:
    return "PNG";
  case ImageFormat::Jpeg:
    return "JPEG";
  case ImageFormat::Webp:
    return "WebP";
  case ImageFormat::Unknown:
    break;
  }
  return "unknown";
}

void check_image_header(const unsigned char* bytes, std::size_t size) {
  const ImageFormat format = sniff_image(bytes, size);
  int w = 0, h = 0, channels = 0;
  WebPBitstreamFeatures features;
  switch (format) {
  case ImageFormat::Png:
  case ImageFormat::Jpeg:
    if (size > std::size_t(std::numeric_limits<int>::max()) ||
        !stbi_info_from_memory(bytes, int(size), &w, &h, &channels))
      throw not_decoding(format, stb_reason());
    return;
  case ImageFormat::Webp:
    if (WebPGetFeatures(bytes, size, &features) != VP8_STATUS_OK)
      throw not_decoding(format, "corrupt data");
    return;
  case ImageFormat::Unknown:
    break;
  }
  throw ImageError("not a PNG, JPEG or WebP image");
}

DecodedImage decode_image(const unsigned char* bytes, std::size_t size, const ImageLimits& limits) {
  const ImageFormat format = sniff_image(bytes, size);
  switch (format) {
  case ImageFormat::Png:
  case ImageFormat::Jpeg:
    return decode_stb(format, bytes, size, limits);
  case ImageFormat::Webp:
    return decode_webp(bytes, size, limits);
  case ImageFormat::Unknown:
    break;
  }
  throw ImageError("not a PNG, JPEG or WebP image");
}

} // namespace irad::gltf
