#include "raster/shadow/shadow_occlusion.h"

#include "core/mesh/hierarchy/mesh_clusters.h"

#include <algorithm>
#include <cmath>

namespace irad::gl {

FaceDepthBound::FaceDepthBound(const float* depth, glm::ivec2 atlas_size, glm::ivec2 offset,
                               glm::ivec4 rect, int resolution)
    : rect_(rect),
      tiles_((rect.z - rect.x + kTile - 1) / kTile, (rect.w - rect.y + kTile - 1) / kTile),
      max_distance_(static_cast<std::size_t>(std::max(tiles_.x * tiles_.y, 0)), 0.0f),
      max_axial_(max_distance_.size(), 0.0f) {
  // Texel (i, j)'s ray through a 90-degree face: (ndc_x, ndc_y, 1) in the face's frame.
  const auto ndc = [&](int i) {
    return (2.0f * static_cast<float>(i) + 1.0f) / static_cast<float>(resolution) - 1.0f;
  };
  for (int j = rect.y; j < rect.w; ++j) {
    const float* row = depth + static_cast<std::size_t>(offset.y + j) * atlas_size.x + offset.x;
    const std::size_t tile_row = static_cast<std::size_t>((j - rect.y) / kTile) * tiles_.x;
    const float v = ndc(j);
    for (int i = rect.x; i < rect.z; ++i) {
      const std::size_t t = tile_row + static_cast<std::size_t>((i - rect.x) / kTile);
      const float u = ndc(i);
      max_distance_[t] = std::max(max_distance_[t], row[i]);
      max_axial_[t] = std::max(max_axial_[t], row[i] / std::sqrt(1.0f + u * u + v * v));
    }
  }
}

bool FaceDepthBound::may_show(const Bounds& box, const glm::mat4& view_projection, int resolution,
                              const glm::vec3& origin, float inv_far) const {
  const float d = distance_to(box, origin) * inv_far;
  if (d <= 0.0f) return true;
  // The box's projection, in face pixels, and its least depth along the axis (clip w).
  glm::vec2 lo(INFINITY), hi(-INFINITY);
  float w_min = INFINITY;
  const float half = 0.5f * static_cast<float>(resolution);
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 corner((c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y,
                           (c & 4) ? box.hi.z : box.lo.z);
    const glm::vec4 clip = view_projection * glm::vec4(corner, 1.0f);
    // A corner at or behind the VPL's plane: the projection is unbounded, keep the box.
    if (!(clip.w > 1e-6f * glm::length(corner - origin))) return true;
    w_min = std::min(w_min, clip.w);
    const glm::vec2 p = (glm::vec2(clip) / clip.w + 1.0f) * half;
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  // Texels whose centre lies in [lo, hi], one more on each side for rounding, within the rect.
  const int i0 = std::max(rect_.x, static_cast<int>(std::ceil(lo.x - 0.5f)) - 1);
  const int i1 = std::min(rect_.z - 1, static_cast<int>(std::floor(hi.x - 0.5f)) + 1);
  const int j0 = std::max(rect_.y, static_cast<int>(std::ceil(lo.y - 0.5f)) - 1);
  const int j1 = std::min(rect_.w - 1, static_cast<int>(std::floor(hi.y - 0.5f)) + 1);
  if (i0 > i1 || j0 > j1) return false; // no texel of the face: clipped away
  float distance = 0.0f, axial = 0.0f;  // the largest stored over those texels' tiles
  for (int tj = (j0 - rect_.y) / kTile; tj <= (j1 - rect_.y) / kTile; ++tj)
    for (int ti = (i0 - rect_.x) / kTile; ti <= (i1 - rect_.x) / kTile; ++ti) {
      const std::size_t t = static_cast<std::size_t>(tj) * tiles_.x + static_cast<std::size_t>(ti);
      distance = std::max(distance, max_distance_[t]);
      axial = std::max(axial, max_axial_[t]);
    }
  // The fragments' depth is float arithmetic on an interpolated point: a relative margin.
  constexpr float kMargin = 1.0f - 1e-5f;
  return d * kMargin <= distance && w_min * inv_far * kMargin <= axial;
}

} // namespace irad::gl
