#include "core/mesh/position_weld.h"

#include "core/util/parallel_rows.h"

#include <bit>
#include <cstring>
#include <memory>
#include <span>

namespace irad {

namespace {

constexpr std::uint32_t kEmpty = ~0u;

// A position's bits mixed to 64 (the parts take the high half, the table slots the low).
std::uint64_t position_hash(const glm::vec3& p) {
  std::uint32_t b[3];
  std::memcpy(b, &p, sizeof b);
  std::uint64_t h = (std::uint64_t{b[0]} << 32 | b[1]) * 0x9E3779B97F4A7C15ull;
  h ^= (std::uint64_t{b[2]} + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
  h ^= h >> 29;
  h *= 0xBF58476D1CE4E5B9ull;
  return h ^ (h >> 32);
}

std::uint32_t part_of(std::uint64_t hash, std::uint32_t parts) {
  return static_cast<std::uint32_t>(((hash >> 32) * parts) >> 32);
}

bool same_bits(const glm::vec3& a, const glm::vec3& b) {
  return std::memcmp(&a, &b, sizeof(glm::vec3)) == 0;
}

// The vertices of one part.
std::size_t part_size(const std::vector<glm::vec3>& positions, std::uint32_t part,
                      std::uint32_t parts) {
  std::size_t count = 0;
  for (const glm::vec3& p : positions) count += part_of(position_hash(p), parts) == part;
  return count;
}

// Table slots for `count` vertices: at most half full, so that probes stay short.
std::size_t table_size(std::size_t count) {
  return std::bit_ceil(std::max<std::size_t>(2 * count, 16));
}

// The vertices of one part welded into `welded` (its entries alone are written), through
// `table` (a power of two of slots).
void weld_part(const std::vector<glm::vec3>& positions, std::uint32_t part, std::uint32_t parts,
               std::span<std::uint32_t> table, std::vector<std::uint32_t>& welded) {
  std::fill(table.begin(), table.end(), kEmpty);
  const std::size_t mask = table.size() - 1;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const std::uint64_t hash = position_hash(positions[v]);
    if (part_of(hash, parts) != part) continue;
    for (std::size_t slot = hash & mask;; slot = (slot + 1) & mask) {
      std::uint32_t& entry = table[slot];
      if (entry == kEmpty) {
        entry = static_cast<std::uint32_t>(v);
        welded[v] = entry;
        break;
      }
      if (same_bits(positions[entry], positions[v])) {
        welded[v] = entry;
        break;
      }
    }
  }
}

} // namespace

std::vector<std::uint32_t> weld_positions(const std::vector<glm::vec3>& positions,
                                          unsigned threads) {
  // Parts of about a million vertices, so that a small mesh stays on one thread.
  const int wanted = static_cast<int>(positions.size() >> 20) + 1;
  const std::uint32_t parts = worker_count(threads, wanted);
  std::vector<std::size_t> first(parts + 1, 0); // each part's slots in one table
  parallel_tasks(static_cast<int>(parts), parts, [&](int part, unsigned) {
    // (One part holds every vertex: nothing to count.)
    const std::size_t count =
        parts == 1 ? positions.size() : part_size(positions, std::uint32_t(part), parts);
    first[std::size_t(part) + 1] = table_size(count);
  });
  for (std::uint32_t part = 0; part < parts; ++part) first[part + 1] += first[part];
  // One allocation for every part's table, given back whole: tables allocated by the threads
  // themselves left 30 MiB of the 10M terrain's heap resident into the tree's build, its peak.
  const std::unique_ptr<std::uint32_t[]> slots(new std::uint32_t[first[parts]]);
  std::vector<std::uint32_t> welded(positions.size());
  parallel_tasks(static_cast<int>(parts), parts, [&](int part, unsigned) {
    const std::span<std::uint32_t> table(slots.get() + first[std::size_t(part)],
                                         slots.get() + first[std::size_t(part) + 1]);
    weld_part(positions, static_cast<std::uint32_t>(part), parts, table, welded);
  });
  return welded;
}

} // namespace irad
