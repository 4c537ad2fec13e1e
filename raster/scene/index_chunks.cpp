#include "raster/scene/index_chunks.h"

#include <algorithm>

namespace irad::gl {

namespace {

// The greedy split: each chunk as long as its span fits kNarrowSpan (a triangle whose own span
// does not fit is a chunk of its own, not narrow).
std::vector<IndexChunk> greedy_chunks(std::span<const std::span<const glm::uvec3>> parts) {
  std::vector<IndexChunk> out;
  std::uint32_t lo = 0, hi = 0;
  const auto close = [&](std::size_t end) {
    IndexChunk& c = out.back();
    c.count = end - c.first;
    c.narrow = hi - lo <= kNarrowSpan;
    c.base = c.narrow ? lo : 0;
  };
  std::size_t t = 0;
  for (std::span<const glm::uvec3> part : parts)
    for (const glm::uvec3& v : part) {
      const std::uint32_t t_lo = std::min({v.x, v.y, v.z}), t_hi = std::max({v.x, v.y, v.z});
      if (!out.empty() && std::max(hi, t_hi) - std::min(lo, t_lo) <= kNarrowSpan) {
        lo = std::min(lo, t_lo), hi = std::max(hi, t_hi);
      } else {
        if (!out.empty()) close(t);
        out.push_back({t, 0, 0, false});
        lo = t_lo, hi = t_hi;
      }
      ++t;
    }
  if (!out.empty()) close(t);
  return out;
}

} // namespace

std::vector<IndexChunk> index_chunks(std::span<const std::span<const glm::uvec3>> parts) {
  std::vector<IndexChunk> greedy = greedy_chunks(parts);
  if (greedy.size() <= 1) return greedy;
  // Short narrow chunks become wide; neighbouring wide chunks merge.
  std::vector<IndexChunk> out;
  for (IndexChunk c : greedy) {
    if (c.narrow && c.count < kMinNarrowTriangles) c = {c.first, c.count, 0, false};
    if (!c.narrow && !out.empty() && !out.back().narrow)
      out.back().count += c.count;
    else
      out.push_back(c);
  }
  return out;
}

std::size_t chunk_bytes(const IndexChunk& c) {
  const std::size_t bytes = 3 * c.count * (c.narrow ? 2 : 4);
  return (bytes + 3) / 4 * 4;
}

} // namespace irad::gl
