#include "irad/compare.h"

namespace irad {

ImageMetrics compare_files(const std::string& image, const std::string& reference, int block) {
  const Image a = read_exr(image);
  const Image b = read_exr(reference);
  require_same_size(a, image, b, reference);
  return compare_images(a, b, block);
}

} // namespace irad
