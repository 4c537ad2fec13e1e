#include "walk/estimators/visibility_tracer.h"

#include "core/util/parallel_rows.h"
#include "walk/estimators/vpl_gather.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <vector>

namespace irad {

namespace {

// The request's records by interleaved set: each set's records light the same pixels.
std::vector<std::vector<std::size_t>> records_by_set(const VisibilityRequest& r) {
  std::map<int, std::vector<std::size_t>> sets;
  for (std::size_t i = 0; i < r.count; ++i) sets[r.sets[i]].push_back(i);
  std::vector<std::vector<std::size_t>> out;
  for (auto& [set, records] : sets) out.push_back(std::move(records));
  return out;
}

// Row ty of the tile of one set (its records `records`): for each tile pixel on the image and on
// a surface, the records' terms there, kVplChunk at a time.
void trace_row(const RayScene& rays, float dmin, const VisibilityRequest& r,
               const std::vector<std::size_t>& records, int ty) {
  const int set = r.sets[records.front()];
  const glm::ivec2 offset(set % r.k, set / r.k);
  const std::size_t plane = static_cast<std::size_t>(r.tile.x) * static_cast<std::size_t>(r.tile.y);
  const Vpl* chunk[kVplChunk];
  glm::vec3 terms[kVplChunk];
  for (int tx = 0; tx < r.tile.x; ++tx) {
    const glm::ivec2 p = r.k * glm::ivec2(tx, ty) + offset;
    if (p.x >= r.width || p.y >= r.height) continue;
    const std::size_t at = static_cast<std::size_t>(p.y) * static_cast<std::size_t>(r.width) +
                           static_cast<std::size_t>(p.x);
    const glm::vec4 position = r.positions[at];
    if (!(position.w > 0.0f)) continue;
    const glm::vec3 n(r.normals[at]);
    const ShadingPoint x{glm::vec3(position), n, n, glm::vec3(0.0f), glm::vec3(0.0f), nullptr};
    const std::size_t texel = static_cast<std::size_t>(ty) * static_cast<std::size_t>(r.tile.x) +
                              static_cast<std::size_t>(tx);
    for (std::size_t first = 0; first < records.size(); first += kVplChunk) {
      const std::size_t n_chunk = std::min(kVplChunk, records.size() - first);
      for (std::size_t i = 0; i < n_chunk; ++i) chunk[i] = r.vpls[records[first + i]];
      vpl_terms(rays, x, chunk, n_chunk, *r.set, dmin, rays.epsilon(), terms);
      for (std::size_t i = 0; i < n_chunk; ++i)
        r.out[records[first + i] * plane + texel] = terms[i] != glm::vec3(0.0f) ? 255 : 0;
    }
  }
}

} // namespace

void trace_visibility(const RayScene& rays, float dmin, const VisibilityRequest& request,
                      unsigned threads) {
  const std::size_t plane =
      static_cast<std::size_t>(request.tile.x) * static_cast<std::size_t>(request.tile.y);
  std::memset(request.out, 0, request.count * plane);
  if (request.count == 0 || plane == 0) return;
  const std::vector<std::vector<std::size_t>> sets = records_by_set(request);
  const int rows = request.tile.y;
  parallel_rows(static_cast<int>(sets.size()) * rows, threads, [&](int task) {
    trace_row(rays, dmin, request, sets[static_cast<std::size_t>(task / rows)], task % rows);
  });
}

} // namespace irad
