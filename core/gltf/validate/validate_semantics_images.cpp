// Images stored in buffer views: no byteStride, and a PNG, JPEG or WebP header that is whole.
// (Images in external files or data URIs are not in the buffers; the loader sees those.)
#include "core/gltf/validate/validate_semantics_read.h"

#include <cstring>

namespace irad::gltf::sem {

using nlohmann::json;

namespace {

enum class Header { Ok, Invalid, Truncated, Unknown };

Header png_header(const unsigned char* p, std::size_t n) {
  // Signature, then the IHDR chunk: length 13, "IHDR", 13 bytes, CRC.
  if (n < 33) return Header::Truncated;
  const unsigned char ihdr_length[4] = {0, 0, 0, 13};
  if (std::memcmp(p + 8, ihdr_length, 4) != 0 || std::memcmp(p + 12, "IHDR", 4) != 0)
    return Header::Invalid;
  return Header::Ok;
}

bool jpeg_frame_marker(unsigned char m) {
  return m >= 0xC0 && m <= 0xCF && m != 0xC4 && m != 0xC8 && m != 0xCC;
}

Header jpeg_header(const unsigned char* p, std::size_t n) {
  // Marker segments after SOI up to the first start-of-frame, each with a length >= 2.
  std::size_t at_byte = 2;
  while (true) {
    if (at_byte + 2 > n) return Header::Truncated;
    if (p[at_byte] != 0xFF) return Header::Invalid;
    const unsigned char marker = p[at_byte + 1];
    if (marker == 0xFF) {
      ++at_byte; // fill byte
      continue;
    }
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) {
      at_byte += 2;
      continue;
    }
    if (marker == 0xD8 || marker == 0xD9 || marker == 0xDA) return Header::Invalid;
    if (at_byte + 4 > n) return Header::Truncated;
    const std::size_t length = std::size_t{p[at_byte + 2]} << 8 | p[at_byte + 3];
    if (length < 2) return Header::Invalid;
    if (jpeg_frame_marker(marker)) {
      if (length < 8) return Header::Invalid;
      return at_byte + 2 + length > n ? Header::Truncated : Header::Ok;
    }
    at_byte += 2 + length;
  }
}

Header webp_header(const unsigned char* p, std::size_t n) {
  if (n < 16) return Header::Truncated;
  if (std::memcmp(p + 12, "VP8 ", 4) != 0 && std::memcmp(p + 12, "VP8L", 4) != 0 &&
      std::memcmp(p + 12, "VP8X", 4) != 0)
    return Header::Invalid;
  return Header::Ok;
}

Header image_header(const unsigned char* p, std::size_t n) {
  static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  if (n >= 8 && std::memcmp(p, kPng, 8) == 0) return png_header(p, n);
  if (n >= 3 && p[0] == 0xFF && p[1] == 0xD8 && p[2] == 0xFF) return jpeg_header(p, n);
  if (n >= 12 && std::memcmp(p, "RIFF", 4) == 0 && std::memcmp(p + 8, "WEBP", 4) == 0)
    return webp_header(p, n);
  return Header::Unknown; // not an error: the validator only warns
}

// The bytes of bufferView `v` when they are all present.
std::optional<std::pair<const unsigned char*, std::size_t>> view_data(const Context& ctx,
                                                                      std::int64_t v) {
  const json* bv = ctx.object("bufferViews", v);
  if (bv == nullptr) return std::nullopt;
  const auto buffer = index(*bv, "buffer");
  const auto length = index(*bv, "byteLength");
  const std::int64_t offset = index(*bv, "byteOffset").value_or(0);
  if (!buffer || !length || *buffer < 0 || !sane(*length) || !sane(offset) ||
      static_cast<std::size_t>(*buffer) >= ctx.buffers.size())
    return std::nullopt;
  const BufferBytes& b = ctx.buffers[static_cast<std::size_t>(*buffer)];
  if (!b.present || b.data == nullptr || static_cast<std::uint64_t>(offset + *length) > b.size)
    return std::nullopt;
  return std::make_pair(b.data + offset, static_cast<std::size_t>(*length));
}

} // namespace

void check_images(const Context& ctx) {
  const json& images = ctx.list("images");
  for (std::size_t i = 0; i < images.size(); ++i) {
    const auto view = index(images[i], "bufferView");
    const json* bv = view ? ctx.object("bufferViews", *view) : nullptr;
    if (bv == nullptr) continue;
    const std::string ptr = at("/images", static_cast<std::int64_t>(i));
    if (has(*bv, "byteStride"))
      ctx.add(at(ptr, "bufferView"), "IMAGE_BUFFER_VIEW_WITH_BYTESTRIDE",
              "a buffer view holding an image cannot have a byteStride");
    const json* ext = member(*bv, "extensions");
    if (ext != nullptr && has(*ext, "EXT_meshopt_compression")) continue;
    const auto data = view_data(ctx, *view);
    if (!data) continue;
    const Header h = image_header(data->first, data->second);
    if (h == Header::Invalid)
      ctx.add(ptr, "IMAGE_DATA_INVALID", "the image's header is malformed");
    else if (h == Header::Truncated)
      ctx.add(ptr, "IMAGE_UNEXPECTED_EOS", "the image data ends inside its header");
  }
}

} // namespace irad::gltf::sem
