#pragma once
// Test images for the docs: with IRAD_TEST_IMAGES=DIR set, tests write PNGs of what they compare,
// side by side, into DIR.
#include "core/image/image.h"
#include "core/image/image_io.h"

#include <cstdlib>
#include <string>
#include <vector>

namespace irad {

// Left to right, each pixel shown as z x z, a gap of 2 black pixels between the images.
inline Image side_by_side(const std::vector<const Image*>& images, int z = 3) {
  int width = 0;
  for (const Image* i : images) width += z * i->width() + 2;
  Image out(width - 2, z * images.front()->height());
  int x0 = 0;
  for (const Image* i : images) {
    for (int y = 0; y < z * i->height(); ++y)
      for (int x = 0; x < z * i->width(); ++x) out.at(x0 + x, y) = i->at(x / z, y / z);
    x0 += z * i->width() + 2;
  }
  return out;
}

// Writes DIR/name.png when IRAD_TEST_IMAGES=DIR is set.
inline void maybe_write_side_by_side(const std::string& name,
                                     const std::vector<const Image*>& images) {
  const char* dir = std::getenv("IRAD_TEST_IMAGES");
  if (dir == nullptr) return;
  write_png(std::string(dir) + "/" + name + ".png", side_by_side(images));
}

} // namespace irad
