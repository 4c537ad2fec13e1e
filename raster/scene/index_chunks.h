#pragma once
// A list of triangles split into runs that GL can draw with 16-bit indices: a narrow chunk's
// vertices all lie in [base, base + 65535], so it is stored as (vertex - base) in 2 bytes an index
// and drawn with glDrawElementsBaseVertex(base); a wide chunk keeps 4-byte indices (base 0). On a
// mesh whose triangles follow its vertices (a grid row by row, the order meshoptimizer's vertex
// cache optimizers leave) almost every triangle lands in a narrow chunk: half the index memory.
//
// The split is greedy in the list's order (the order of the draw, which gl_PrimitiveID counts,
// is kept): a chunk grows while its vertices' span fits 16 bits. Narrow chunks of fewer than
// kMinNarrowTriangles are made wide and merged with their wide neighbours, so that a list in no
// vertex order costs a few draws, not one per triangle. A list whose span fits 16 bits is one
// narrow chunk.
#include <glm/glm.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace irad::gl {

struct IndexChunk {
  std::size_t first = 0, count = 0; // triangles of the list
  std::uint32_t base = 0;           // the smallest vertex (narrow); 0 (wide)
  bool narrow = false;
};

inline constexpr std::size_t kMinNarrowTriangles = 1024;
inline constexpr std::uint32_t kNarrowSpan = 65535; // the largest vertex - base of a narrow chunk

// The chunks of the list that is `parts` one after the other, in order, covering it once.
std::vector<IndexChunk> index_chunks(std::span<const std::span<const glm::uvec3>> parts);

// Calls f(triangle) for triangles [first, first + count) of the list that is `parts` one after
// the other.
template <class F>
void for_each_triangle(std::span<const std::span<const glm::uvec3>> parts, std::size_t first,
                       std::size_t count, F&& f) {
  for (std::span<const glm::uvec3> part : parts) {
    if (count == 0) return;
    if (first >= part.size()) {
      first -= part.size();
      continue;
    }
    const std::size_t n = std::min(count, part.size() - first);
    for (std::size_t t = first; t < first + n; ++t) f(part[t]);
    first = 0, count -= n;
  }
}

// Bytes of the chunks' indices (2 or 4 each), every chunk starting on a 4-byte boundary.
std::size_t chunk_bytes(const IndexChunk& c);

} // namespace irad::gl
