#pragma once
// A part of a mesh renumbered over the vertices it uses, for the tools that work on the part alone
// (meshoptimizer scales by every vertex it is given; the planar reduction's fans are per vertex):
// the shadow hierarchy's simplifications (core/mesh/hierarchy/cluster_levels.cpp) and the planar
// reduction's chunks (core/mesh/planar/planar_chunks.cpp). The map from the mesh's vertices is
// as long as the mesh's vertex array, so each worker of parallel_tasks keeps one (LocalMaps) and
// every call leaves it as it found it.
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace irad {

inline constexpr std::uint32_t kNoLocal = ~0u;

// Per worker, a map from the mesh's vertices to local numbers, kNoLocal between calls; made on the
// worker's first call.
class LocalMaps {
public:
  LocalMaps(std::size_t vertices, unsigned workers) : vertices_(vertices), maps_(workers) {}
  std::vector<std::uint32_t>& of(unsigned worker) {
    std::vector<std::uint32_t>& m = maps_[worker];
    if (m.empty()) m.assign(vertices_, kNoLocal);
    return m;
  }

private:
  std::size_t vertices_;
  std::vector<std::vector<std::uint32_t>> maps_;
};

// `indices` (the mesh's vertices) renumbered in order of first use: local[k] is indices[k]'s
// number, global[l] the mesh's vertex numbered l.
struct LocalVertices {
  std::vector<std::uint32_t> local, global;
};

// The renumbering of `indices` through a hash table of its own (open addressing, twice the
// indices' slots): the same numbers as through a map, for a caller that renumbers too few parts
// to pay for a map as long as the mesh's vertex array.
inline LocalVertices local_vertices(std::span<const std::uint32_t> indices) {
  std::size_t size = 16;
  while (size < 2 * indices.size()) size *= 2;
  // slot: (vertex + 1, local number); vertex + 1 == 0 marks a free slot.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> table(size, {0u, 0u});
  LocalVertices out;
  out.local.resize(indices.size());
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const std::uint32_t v = indices[k];
    std::size_t h = (std::size_t{v} * 0x9E3779B1u) & (size - 1);
    while (table[h].first != 0 && table[h].first != v + 1) h = (h + 1) & (size - 1);
    if (table[h].first == 0) {
      table[h] = {v + 1, static_cast<std::uint32_t>(out.global.size())};
      out.global.push_back(v);
    }
    out.local[k] = table[h].second;
  }
  return out;
}

// The renumbering of `indices`; `map` (a LocalMaps map) is all kNoLocal before and after.
inline LocalVertices local_vertices(std::span<const std::uint32_t> indices,
                                    std::vector<std::uint32_t>& map) {
  LocalVertices out;
  out.local.resize(indices.size());
  for (std::size_t k = 0; k < indices.size(); ++k) {
    std::uint32_t& l = map[indices[k]];
    if (l == kNoLocal) {
      l = static_cast<std::uint32_t>(out.global.size());
      out.global.push_back(indices[k]);
    }
    out.local[k] = l;
  }
  for (std::uint32_t g : out.global) map[g] = kNoLocal;
  return out;
}

} // namespace irad
