#include "core/mesh/hierarchy/late_levels_file.h"

#include "core/mesh/hierarchy/hashed_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <meshoptimizer.h>
#include <vector>

namespace irad {

namespace fs = std::filesystem;
using namespace cache_io;

namespace {

constexpr char kLateMagic[8] = {'I', 'R', 'A', 'D', 'L', 'V', 'L', '\0'};

struct LateHeader {
  char magic[8];
  std::uint32_t format, meshopt;
  std::uint64_t key_low, key_high;
  std::uint64_t nodes, index_count;       // the hierarchy's: its nodes, its indices
  std::uint64_t entries, levels, indices; // this file's
};
static_assert(sizeof(LateHeader) == 72, "the late header has no padding");

LateHeader late_header(const MeshClusters& c, const ClusterKey& key, std::size_t levels) {
  LateHeader h{};
  std::memcpy(h.magic, kLateMagic, sizeof kLateMagic);
  h.format = kClusterCacheFormat;
  h.meshopt = MESHOPTIMIZER_VERSION;
  h.key_low = key.low;
  h.key_high = key.high;
  h.nodes = c.nodes.size();
  h.index_count = c.index_count();
  h.entries = c.late_nodes.size();
  h.levels = levels;
  h.indices = c.late_indices.size();
  return h;
}

// The late file's parts: per node (node, levels_count), its levels (error, first from the late
// base, count), the late indices.
struct LateParts {
  std::vector<std::uint32_t> entries, levels, indices;
};

// Whether `p` (read under a matching header) fits c: its nodes pending in c, its levels in its
// indices with errors finite and at least their node's, every index below `vertices`, the index
// space within 32 bits (a level's first, late base added, must not wrap).
bool late_parts_fit(const LateParts& p, const MeshClusters& c, std::size_t vertices) {
  if (c.late_base() + p.indices.size() > std::numeric_limits<std::uint32_t>::max()) return false;
  std::size_t level = 0;
  std::vector<bool> seen(c.nodes.size(), false);
  for (std::size_t e = 0; e + 1 < p.entries.size(); e += 2) {
    const std::uint32_t n = p.entries[e], count = p.entries[e + 1];
    if (n >= c.nodes.size() || seen[n] || !c.nodes[n].levels_pending()) return false;
    seen[n] = true;
    if (count > p.levels.size() / 3 - level) return false;
    for (std::uint32_t k = 0; k < count; ++k, ++level) {
      const float error = from_word<float>(p.levels[3 * level]);
      const std::uint64_t first = p.levels[3 * level + 1], n_indices = p.levels[3 * level + 2];
      if (!std::isfinite(error) || error < c.nodes[n].error || n_indices % 3 != 0 ||
          first + n_indices > p.indices.size())
        return false;
    }
  }
  return level * 3 == p.levels.size() && below(p.indices.data(), p.indices.size(), vertices);
}

bool write_late_file(const fs::path& to, const MeshClusters& c, const ClusterKey& key) {
  LateParts p;
  std::vector<std::int32_t> nodes = c.late_nodes;
  std::sort(nodes.begin(), nodes.end());
  const std::size_t base = c.late_base();
  for (std::int32_t n : nodes) {
    const ClusterNode& node = c.nodes[static_cast<std::size_t>(n)];
    p.entries.insert(p.entries.end(), {static_cast<std::uint32_t>(n), node.levels_count});
    for (std::uint32_t l = node.levels_first; l < node.levels_first + node.levels_count; ++l) {
      const ClusterLevel& level = c.levels[l];
      p.levels.insert(
          p.levels.end(),
          {word(level.error), static_cast<std::uint32_t>(level.first - base), level.count});
    }
  }
  HashedWriter w(to);
  const LateHeader h = late_header(c, key, p.levels.size() / 3);
  w.bytes(&h, sizeof h);
  w.values(p.entries);
  w.values(p.levels);
  w.values(c.late_indices);
  return w.finish();
}

} // namespace

fs::path late_levels_path(const fs::path& file) {
  fs::path p = file;
  return p.replace_extension(".lvl");
}

std::size_t read_late_levels(const fs::path& file, const ClusterKey& key, std::size_t vertices,
                             MeshClusters& c) noexcept {
  try {
    const auto in = std::make_shared<const OpenFile>(late_levels_path(file));
    if (!in->valid() || !c.late_nodes.empty()) return 0;
    const std::uint64_t size = in->size();
    HashedReader r(in);
    LateHeader h{};
    if (!r.bytes(&h, sizeof h) || std::memcmp(h.magic, kLateMagic, sizeof kLateMagic) != 0 ||
        h.format != kClusterCacheFormat || h.meshopt != MESHOPTIMIZER_VERSION ||
        h.key_low != key.low || h.key_high != key.high || h.nodes != c.nodes.size() ||
        h.index_count != c.index_count())
      return 0;
    if (h.entries > size || h.levels > size || h.indices > size ||
        sizeof h + 4 * (2 * h.entries + 3 * h.levels + h.indices) + sizeof(std::uint64_t) != size)
      return 0;
    LateParts p;
    if (!r.values(p.entries, 2 * h.entries) || !r.values(p.levels, 3 * h.levels) ||
        !r.values(p.indices, h.indices) || !r.checksum_matches() || !late_parts_fit(p, c, vertices))
      return 0;
    const std::size_t base = c.late_base();
    c.late_indices = std::move(p.indices);
    for (std::size_t e = 0, level = 0; e < p.entries.size(); e += 2) {
      ClusterNode& node = c.nodes[p.entries[e]];
      node.levels_first = static_cast<std::uint32_t>(c.levels.size());
      node.levels_count = p.entries[e + 1];
      for (std::uint32_t k = 0; k < node.levels_count; ++k, ++level)
        c.levels.push_back({from_word<float>(p.levels[3 * level]),
                            static_cast<std::uint32_t>(base + p.levels[3 * level + 1]),
                            p.levels[3 * level + 2]});
      c.late_nodes.push_back(static_cast<std::int32_t>(p.entries[e]));
    }
    return c.late_nodes.size();
  } catch (const std::exception&) { // memory: the levels are built again as needed
    return 0;
  }
}

bool write_late_levels(const fs::path& file, const ClusterKey& key, const MeshClusters& c,
                       std::string& why) noexcept {
  try {
    return write_atomically(
        late_levels_path(file), [&](const fs::path& to) { return write_late_file(to, c, key); },
        why);
  } catch (const std::exception& e) {
    why = e.what();
    return false;
  }
}

} // namespace irad
