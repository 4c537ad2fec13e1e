#pragma once
// Internal to the glTF loader: decoding of glTF images (PNG and JPEG through stb_image, WebP
// through libwebp) within irad's limits, with irad's own messages (no decoder text passes
// through raw).
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace irad::gltf {

enum class ImageFormat { Png, Jpeg, Webp, Unknown };

// The format the bytes' signature says (PNG: 89 50 4E 47 0D 0A 1A 0A; JPEG: FF D8 FF; WebP:
// "RIFF" ???? "WEBP").
ImageFormat sniff_image(const unsigned char* bytes, std::size_t size);
const char* image_format_name(ImageFormat format); // "PNG", "JPEG", "WebP", "unknown"

struct DecodedImage {
  int width = 0;
  int height = 0;
  int channels = 0;                  // 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA
  int bits = 8;                      // 8 or 16 per channel (16: native-endian std::uint16_t values)
  std::vector<unsigned char> pixels; // row-major, row 0 the top of the image
};

// Thrown by decode_image; what() is one line in irad's words, e.g. "the PNG does not decode
// (corrupt data)" or "4096 x 4096 texels exceed --max-texture-size 2048".
class ImageError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct ImageLimits {
  int max_side = 8192;                 // texels per side
  std::uint64_t max_texels = 1u << 26; // of this image
};

// Reads only the header of PNG, JPEG or WebP bytes (no pixel is decoded) and throws ImageError
// as decode_image would for an unknown format or a header that does not parse.
void check_image_header(const unsigned char* bytes, std::size_t size);

// Decodes PNG, JPEG or WebP bytes. The size is read from the header and checked against the
// limits before any pixel is decoded. Channels are the file's: PNG and JPEG as stored (a grey or
// RGB PNG's tRNS colour key becomes an alpha channel; palettes expand to RGB or RGBA), 16-bit
// PNGs as 16 bits; WebP as RGBA when it has alpha, else RGB. Refused: animated WebPs, PNGs whose
// first IDAT chunk is empty (stb_image mishandles them), sizes beyond int. Thread-safe.
DecodedImage decode_image(const unsigned char* bytes, std::size_t size, const ImageLimits& limits);

} // namespace irad::gltf
