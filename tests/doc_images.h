#pragma once
// Pictures for the documentation, written by some tests only when the environment variable
// IRAD_DOC_IMAGES names a directory (never in a normal test run): images side by side, crops
// magnified with nearest-neighbour, masks.
#include "core/image/image.h"
#include "core/image/image_io.h"

#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <vector>

namespace irad::doc_images {

// The directory, or empty when no pictures are wanted.
inline std::filesystem::path directory() {
  const char* d = std::getenv("IRAD_DOC_IMAGES");
  return d ? std::filesystem::path(d) : std::filesystem::path();
}

// The images left to right (same height), separated by `gap` white-ish columns.
inline Image side_by_side(std::initializer_list<const Image*> images, int gap = 2) {
  int w = 0, h = 0;
  for (const Image* i : images) {
    w += i->width() + gap;
    h = std::max(h, i->height());
  }
  Image out(w - gap, h);
  for (auto& p : out.pixels()) p = glm::vec4(1.0f);
  int x0 = 0;
  for (const Image* i : images) {
    for (int y = 0; y < i->height(); ++y)
      for (int x = 0; x < i->width(); ++x) out.at(x0 + x, y) = i->at(x, y);
    x0 += i->width() + gap;
  }
  return out;
}

// The w x h window at (x0, y0), each pixel repeated f x f times.
inline Image magnified_crop(const Image& image, int x0, int y0, int w, int h, int f) {
  Image out(w * f, h * f);
  for (int y = 0; y < h * f; ++y)
    for (int x = 0; x < w * f; ++x) out.at(x, y) = image.at(x0 + x / f, y0 + y / f);
  return out;
}

// A 0/1 mask as a grey image over a dimmed copy of `image`: mask pixels in yellow.
inline Image mask_overlay(const Image& image, const std::vector<std::uint8_t>& mask) {
  Image out(image.width(), image.height());
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      out.at(x, y) = mask[static_cast<std::size_t>(y * image.width() + x)]
                         ? glm::vec4(1.0f, 0.8f, 0.0f, 1.0f)
                         : 0.3f * image.at(x, y);
  return out;
}

inline void write(const std::string& name, const Image& image, float exposure = 0.0f) {
  const std::filesystem::path dir = directory();
  if (dir.empty()) return;
  std::filesystem::create_directories(dir);
  PngOptions png;
  png.exposure = exposure;
  write_png(dir / name, image, png);
}

} // namespace irad::doc_images
