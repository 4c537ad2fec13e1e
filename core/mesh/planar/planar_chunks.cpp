#include "core/mesh/planar/planar_chunks.h"

#include "core/mesh/local_vertices.h"
#include "core/util/parallel_rows.h"

#include <algorithm>
#include <atomic>
#include <glm/glm.hpp>
#include <limits>

namespace irad {

namespace {

constexpr std::uint32_t kNoChunk = std::numeric_limits<std::uint32_t>::max(); // owners
constexpr std::uint32_t kSharedVertex = kNoChunk - 1;

struct ChunkRange {
  std::size_t first = 0, end = 0;
  std::size_t size() const { return end - first; }
};

// A triangle's centroid beside its index: the splits move both together, so that each reads its
// range in order.
struct Centred {
  glm::vec3 centroid;
  std::uint32_t triangle;
};

// Splits items[r] at its middle: the half with the smaller centroids along the longest axis of
// their bounds first (ties by index, so the split is the same on every run).
std::array<ChunkRange, 2> split_at_median(std::vector<Centred>& items, ChunkRange r) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (std::size_t k = r.first; k < r.end; ++k) {
    lo = glm::min(lo, items[k].centroid);
    hi = glm::max(hi, items[k].centroid);
  }
  const glm::vec3 extent = hi - lo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  const std::size_t middle = r.first + r.size() / 2;
  const auto begin = items.begin();
  std::nth_element(begin + std::ptrdiff_t(r.first), begin + std::ptrdiff_t(middle),
                   begin + std::ptrdiff_t(r.end), [axis](const Centred& a, const Centred& b) {
                     const float ka = a.centroid[axis], kb = b.centroid[axis];
                     return ka != kb ? ka < kb : a.triangle < b.triangle;
                   });
  return {ChunkRange{r.first, middle}, ChunkRange{middle, r.end}};
}

// Per vertex: the one chunk whose triangles use it, kSharedVertex where two or more do, kNoChunk
// where none does. The chunks on all cores, each vertex's mark moved on atomically (none -> its
// chunk -> shared), which gives the same marks in any order.
std::vector<std::uint32_t> vertex_owners(const std::vector<glm::uvec3>& triangles,
                                         const std::vector<std::vector<std::uint32_t>>& chunks,
                                         std::size_t vertices, unsigned threads) {
  std::vector<std::uint32_t> owner(vertices, kNoChunk);
  parallel_tasks(static_cast<int>(chunks.size()), threads, [&](int task, unsigned) {
    const auto c = static_cast<std::uint32_t>(task);
    for (std::uint32_t t : chunks[c])
      for (int k = 0; k < 3; ++k) {
        std::atomic_ref<std::uint32_t> o(owner[triangles[t][k]]);
        std::uint32_t now = o.load(std::memory_order_relaxed);
        while (now != c && now != kSharedVertex &&
               !o.compare_exchange_weak(now, now == kNoChunk ? c : kSharedVertex,
                                        std::memory_order_relaxed)) {
        }
      }
  });
  return owner;
}

// Each chunk's triangles in ascending order, from every triangle's chunk (`chunk_of`) and the
// chunks' sizes: the triangles in parts, each part's triangles counted per chunk, then written
// at its offset in each chunk's list (a counting sort by chunk, stable), the parts on all cores.
std::vector<std::vector<std::uint32_t>> deal_to_chunks(const std::vector<std::uint32_t>& chunk_of,
                                                       const std::vector<ChunkRange>& chunks,
                                                       unsigned threads) {
  constexpr std::size_t kPart = std::size_t{1} << 18;
  const std::size_t count = chunk_of.size(), n = chunks.size();
  const std::size_t parts = (count + kPart - 1) / kPart;
  std::vector<std::uint32_t> at(parts * n, 0); // part p, chunk c: at[p * n + c]
  parallel_tasks(static_cast<int>(parts), threads, [&](int p, unsigned) {
    const std::size_t first = static_cast<std::size_t>(p) * kPart;
    for (std::size_t t = first; t < std::min(count, first + kPart); ++t)
      ++at[static_cast<std::size_t>(p) * n + chunk_of[t]];
  });
  for (std::size_t c = 0; c < n; ++c) {
    std::uint32_t offset = 0;
    for (std::size_t p = 0; p < parts; ++p) {
      const std::uint32_t k = at[p * n + c];
      at[p * n + c] = offset;
      offset += k;
    }
  }
  std::vector<std::vector<std::uint32_t>> out(n);
  parallel_tasks(static_cast<int>(n), threads, [&](int c, unsigned) {
    out[std::size_t(c)].resize(chunks[std::size_t(c)].size());
  });
  parallel_tasks(static_cast<int>(parts), threads, [&](int p, unsigned) {
    const std::size_t first = static_cast<std::size_t>(p) * kPart;
    std::uint32_t* next = at.data() + static_cast<std::size_t>(p) * n;
    for (std::size_t t = first; t < std::min(count, first + kPart); ++t)
      out[chunk_of[t]][next[chunk_of[t]]++] = static_cast<std::uint32_t>(t);
  });
  return out;
}

// One chunk reduced over its own vertices (`map`: a LocalMaps map), its shared vertices locked;
// the result in the mesh's vertices.
PlanarReduction reduce_chunk(const std::vector<glm::vec3>& positions,
                             const std::vector<glm::uvec3>& triangles,
                             const std::vector<std::uint32_t>& chunk,
                             const std::vector<std::uint32_t>& owner, float epsilon,
                             std::vector<std::uint32_t>& map) {
  std::vector<std::uint32_t> corners(3 * chunk.size());
  for (std::size_t k = 0; k < chunk.size(); ++k)
    for (int c = 0; c < 3; ++c) corners[3 * k + std::size_t(c)] = triangles[chunk[k]][c];
  const LocalVertices v = local_vertices(corners, map);
  std::vector<glm::vec3> own_positions(v.global.size());
  std::vector<bool> locked(v.global.size());
  for (std::size_t l = 0; l < v.global.size(); ++l) {
    own_positions[l] = positions[v.global[l]];
    locked[l] = owner[v.global[l]] == kSharedVertex;
  }
  std::vector<glm::uvec3> own_triangles(chunk.size());
  for (std::size_t k = 0; k < chunk.size(); ++k)
    own_triangles[k] = {v.local[3 * k], v.local[3 * k + 1], v.local[3 * k + 2]};
  PlanarReduction r = reduce_planar(own_positions, own_triangles, epsilon, locked);
  for (glm::uvec3& t : r.triangles) t = {v.global[t.x], v.global[t.y], v.global[t.z]};
  return r;
}

} // namespace

std::vector<std::vector<std::uint32_t>> spatial_chunks(const std::vector<glm::vec3>& positions,
                                                       const std::vector<glm::uvec3>& triangles,
                                                       std::size_t chunk, unsigned threads) {
  std::vector<Centred> items(triangles.size());
  parallel_chunks(triangles.size(), [&](std::size_t first, std::size_t end) {
    for (std::size_t t = first; t < end; ++t) {
      const glm::uvec3& v = triangles[t];
      items[t] = {(positions[v.x] + positions[v.y] + positions[v.z]) / 3.0f,
                  static_cast<std::uint32_t>(t)};
    }
  });
  std::vector<ChunkRange> level, done;
  (triangles.size() > chunk ? level : done).push_back({0, triangles.size()});
  while (!level.empty()) {
    std::vector<std::array<ChunkRange, 2>> halves(level.size());
    parallel_tasks(static_cast<int>(level.size()), threads, [&](int k, unsigned) {
      halves[std::size_t(k)] = split_at_median(items, level[std::size_t(k)]);
    });
    level.clear();
    for (const auto& pair : halves)
      for (const ChunkRange& r : pair) (r.size() > chunk ? level : done).push_back(r);
  }
  std::sort(done.begin(), done.end(),
            [](const ChunkRange& a, const ChunkRange& b) { return a.first < b.first; });
  // Each chunk's triangles in ascending order: every triangle marked with its chunk, then the
  // triangles in order dealt to their chunks (instead of a sort per chunk).
  std::vector<std::uint32_t> chunk_of(triangles.size());
  parallel_tasks(static_cast<int>(done.size()), threads, [&](int k, unsigned) {
    const ChunkRange r = done[std::size_t(k)];
    for (std::size_t i = r.first; i < r.end; ++i)
      chunk_of[items[i].triangle] = static_cast<std::uint32_t>(k);
  });
  items = {};
  return deal_to_chunks(chunk_of, done, threads);
}

PlanarReduction reduce_planar_chunked(const std::vector<glm::vec3>& positions,
                                      const std::vector<glm::uvec3>& triangles, float epsilon,
                                      std::size_t chunk, unsigned threads) {
  if (triangles.size() <= chunk) return reduce_planar(positions, triangles, epsilon);
  const std::vector<std::vector<std::uint32_t>> chunks =
      spatial_chunks(positions, triangles, chunk, threads);
  const std::vector<std::uint32_t> owner =
      vertex_owners(triangles, chunks, positions.size(), threads);
  LocalMaps local(positions.size(), worker_count(threads, static_cast<int>(chunks.size())));
  std::vector<PlanarReduction> parts(chunks.size());
  parallel_tasks(static_cast<int>(chunks.size()), threads, [&](int k, unsigned worker) {
    parts[std::size_t(k)] = reduce_chunk(positions, triangles, chunks[std::size_t(k)], owner,
                                         epsilon, local.of(worker));
  });
  PlanarReduction out;
  std::size_t total = 0;
  for (const PlanarReduction& p : parts) total += p.triangles.size();
  out.triangles.reserve(total);
  for (PlanarReduction& p : parts) {
    out.triangles.insert(out.triangles.end(), p.triangles.begin(), p.triangles.end());
    out.patches += p.patches;
    out.collapses += p.collapses;
    p = {};
  }
  return out;
}

} // namespace irad
