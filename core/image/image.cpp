#include "core/image/image.h"

#include <algorithm>
#include <cmath>

namespace irad {

// Counts pixels, not channels: a pixel with any NaN or +-Inf channel (alpha included) counts once.
std::size_t Image::non_finite_count() const {
  return static_cast<std::size_t>(
      std::count_if(pixels_.begin(), pixels_.end(), [](const glm::vec4& p) {
        return !(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) &&
                 std::isfinite(p.w));
      }));
}

} // namespace irad
