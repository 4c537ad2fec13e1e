#pragma once
// Image files. EXR: linear float RGBA (OpenEXR 3, 32-bit float channels, ZIP compression).
// PNG: display-referred 8-bit sRGB after exposure and a tone map (see ToneMap).
#include "core/image/image.h"

#include <filesystem>
#include <map>
#include <string>

namespace irad {

enum class ToneMap {
  Clamp,    // v = clamp(2^EV * L, 0, 1): linear up to white, then clipped (the default)
  Reinhard, // v = x / (1 + x) per channel with x = 2^EV * L
};

struct PngOptions {
  float exposure = 0.0f; // EV stops: radiance is scaled by 2^exposure before the tone map
  ToneMap tone_map = ToneMap::Clamp;
};

enum class ImageFormat { Exr, Png };

// Format from the extension (.exr, .png, case-insensitive); throws irad::Error naming the file
// for anything else.
ImageFormat image_format_of(const std::filesystem::path& path);

// Writes by extension. Throws irad::Error naming the file when it cannot be written.
void write_image(const std::filesystem::path& path, const Image& image, const PngOptions& png = {});
// String attributes of an EXR header (name -> value; irad's part headers use "irad.*" names).
using ExrAttributes = std::map<std::string, std::string>;
void write_exr(const std::filesystem::path& path, const Image& image,
               const ExrAttributes& attributes = {});
void write_png(const std::filesystem::path& path, const Image& image, const PngOptions& png = {});
// Reads R, G, B (and A when present, else 1) of an EXR as float, and, when `attributes` is not
// null, every string attribute of its header. Throws irad::Error.
Image read_exr(const std::filesystem::path& path, ExrAttributes* attributes = nullptr);

// The display value in [0,1] (before sRGB encoding) of one linear channel.
float tone_map(float linear, const PngOptions& png);
// sRGB encoding of a display value in [0,1].
float linear_to_srgb(float c);

} // namespace irad
