#include "core/mesh/hierarchy/cluster_cache.h"

#include "core/mesh/hierarchy/hashed_file.h"
#include "core/mesh/hierarchy/late_levels_file.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <functional>
#include <memory>
#include <meshoptimizer.h>
#include <system_error>
#include <unistd.h>
#include <vector>
#include <xxhash.h>

namespace irad {

namespace fs = std::filesystem;
using namespace cache_io;

namespace {

constexpr char kMagic[8] = {'I', 'R', 'A', 'D', 'L', 'O', 'D', '\0'};
constexpr std::size_t kNodeWords = 15; // a node as 32-bit words (write_node)
constexpr std::size_t kLevelWords = 3; // a level as 32-bit words
// indices, nodes, roots, levels, triangles, original, root materials
constexpr std::size_t kCountFields = 7;

std::array<std::uint32_t, kNodeWords> node_words(const ClusterNode& n) {
  return {word(n.bounds.lo.x), word(n.bounds.lo.y), word(n.bounds.lo.z), word(n.bounds.hi.x),
          word(n.bounds.hi.y), word(n.bounds.hi.z), word(n.error),       n.mesh_first,
          n.mesh_count,        n.leaf_first,        n.leaf_count,        word(n.children[0]),
          word(n.children[1]), n.levels_first,      n.levels_count};
}
ClusterNode node_from(const std::uint32_t* w) {
  ClusterNode n;
  n.bounds.lo = {from_word<float>(w[0]), from_word<float>(w[1]), from_word<float>(w[2])};
  n.bounds.hi = {from_word<float>(w[3]), from_word<float>(w[4]), from_word<float>(w[5])};
  n.error = from_word<float>(w[6]);
  n.mesh_first = w[7];
  n.mesh_count = w[8];
  n.leaf_first = w[9];
  n.leaf_count = w[10];
  n.children[0] = from_word<std::int32_t>(w[11]);
  n.children[1] = from_word<std::int32_t>(w[12]);
  n.levels_first = w[13];
  n.levels_count = w[14];
  return n;
}

struct Header {
  char magic[8];
  std::uint32_t format, meshopt;
  std::uint32_t deferred_max_levels, deferred_step; // MeshClusters's
  std::uint64_t key_low, key_high;
  std::uint64_t counts[kCountFields];
};
static_assert(sizeof(Header) == 96, "the header has no padding");

// The file's size for a header's counts (whether it can hold them at all is the caller's).
std::uintmax_t expected_size(const Header& h) {
  const auto& c = h.counts;
  return sizeof(Header) + 4 * (c[0] + kNodeWords * c[1] + c[2] + kLevelWords * c[3] + c[4] + c[6]) +
         sizeof(std::uint64_t);
}

// The header write_file gives c (its indices in memory) under `key`.
Header header_of(const MeshClusters& c, const ClusterKey& key) {
  Header h{};
  std::memcpy(h.magic, kMagic, sizeof kMagic);
  h.format = kClusterCacheFormat;
  h.meshopt = MESHOPTIMIZER_VERSION;
  h.deferred_max_levels = static_cast<std::uint32_t>(c.deferred_max_levels);
  h.deferred_step = static_cast<std::uint32_t>(c.deferred_step);
  h.key_low = key.low;
  h.key_high = key.high;
  const std::uint64_t counts[kCountFields] = {
      c.index_count(),    c.nodes.size(),     c.roots.size(),         c.levels.size(),
      c.triangles.size(), c.original_indices, c.root_materials.size()};
  std::memcpy(h.counts, counts, sizeof counts);
  return h;
}

bool write_file(const fs::path& path, const MeshClusters& c, const ClusterKey& key) {
  HashedWriter w(path);
  const Header h = header_of(c, key);
  w.bytes(&h, sizeof h);
  // Its indices in memory: its own, or shared with its user (held while written).
  const auto shared = c.stored_indices ? c.stored_indices->in_memory() : nullptr;
  w.values(shared ? *shared : c.indices);
  std::vector<std::uint32_t> words;
  words.reserve(c.nodes.size() * kNodeWords);
  for (const ClusterNode& n : c.nodes) {
    const auto nw = node_words(n);
    words.insert(words.end(), nw.begin(), nw.end());
  }
  w.values(words);
  w.values(c.roots);
  words.clear();
  for (const ClusterLevel& l : c.levels) {
    words.push_back(word(l.error));
    words.push_back(l.first);
    words.push_back(l.count);
  }
  w.values(words);
  w.values(c.triangles);
  w.values(c.root_materials);
  return w.finish();
}

// The hierarchy in `path` for `key`, or "" in `why` and the hierarchy; else why not.
MeshClusters read_file(const fs::path& path, const ClusterKey& key, const Scene& scene,
                       std::string& why) {
  const std::size_t vertices = scene.positions.size();
  MeshClusters c;
  const auto file = std::make_shared<const OpenFile>(path);
  const std::uint64_t size = file->size();
  HashedReader r(file);
  Header h{};
  if (!file->valid() || !r.bytes(&h, sizeof h)) {
    why = "unreadable or shorter than its header";
    return c;
  }
  if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0 || h.format != kClusterCacheFormat ||
      h.meshopt != MESHOPTIMIZER_VERSION) {
    why = "another format or meshoptimizer version";
    return c;
  }
  if (h.key_low != key.low || h.key_high != key.high) {
    why = "the key of another scene";
    return c;
  }
  // Counts a file of this size can hold (so that a flipped count allocates nothing absurd).
  for (std::uint64_t n : h.counts)
    if (n > size) {
      why = "sizes beyond the file";
      return c;
    }
  if (expected_size(h) != size) {
    why = "truncated or padded";
    return c;
  }
  // The indices (the file's bulk) are checked as they stream past and left in the file.
  const std::uint64_t indices_at = r.offset();
  bool indices_below = false;
  std::vector<std::uint32_t> words;
  bool ok =
      r.indices(h.counts[0], vertices, indices_below) && r.values(words, h.counts[1] * kNodeWords);
  for (std::size_t k = 0; ok && k < h.counts[1]; ++k)
    c.nodes.push_back(node_from(&words[k * kNodeWords]));
  ok = ok && r.values(c.roots, h.counts[2]) && r.values(words, h.counts[3] * kLevelWords);
  for (std::size_t k = 0; ok && k < h.counts[3]; ++k)
    c.levels.push_back({from_word<float>(words[k * kLevelWords]), words[k * kLevelWords + 1],
                        words[k * kLevelWords + 2]});
  ok = ok && r.values(c.triangles, h.counts[4]) && r.values(c.root_materials, h.counts[6]);
  c.original_indices = h.counts[5];
  c.deferred_max_levels = static_cast<int>(std::min<std::uint32_t>(h.deferred_max_levels, 1024));
  c.deferred_step = static_cast<int>(std::min<std::uint32_t>(h.deferred_step, 1024));
  if (!ok || !r.checksum_matches()) {
    why = "checksum mismatch";
    return {};
  }
  if (!indices_below) {
    why = "an index past the vertices";
    return {};
  }
  c.stored_indices = std::make_shared<const StoredIndices>(
      file, indices_at, static_cast<std::size_t>(h.counts[0]), vertices);
  why = validate_clusters(c, vertices, scene.triangle_count(), scene.materials.size());
  if (!why.empty()) return {};
  return c;
}

// After c was written to `path`: its indices from there (as a hit has them), their memory freed
// (indices shared with another user: StoredIndices::leave_in_file, for both), when the file opens
// and has the size c's counts give; else c as it is.
void leave_indices_in(const fs::path& path, const ClusterKey& key, std::size_t vertices,
                      MeshClusters& c) {
  const auto file = std::make_shared<const OpenFile>(path);
  if (!file->valid() || file->size() != expected_size(header_of(c, key))) return;
  if (c.stored_indices) {
    c.stored_indices->leave_in_file(file, sizeof(Header), vertices);
    return;
  }
  c.stored_indices =
      std::make_shared<const StoredIndices>(file, sizeof(Header), c.index_count(), vertices);
  std::vector<std::uint32_t>().swap(c.indices);
}

// Removes the least recently used files (hierarchies, walk/walls/wall_cache.h's walls) until the
// folder holds at most kCacheBytes, and temporary files an hour old (a writer that died).
void trim_folder(const fs::path& folder) {
  std::error_code ec;
  std::vector<std::pair<fs::file_time_type, fs::path>> files;
  std::uintmax_t total = 0;
  const auto now = fs::file_time_type::clock::now();
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
    const fs::path& p = e.path();
    const fs::file_time_type t = e.last_write_time(ec);
    if (ec) continue;
    if (p.filename().string().find(".tmp.") != std::string::npos) {
      if (now - t > std::chrono::hours(1)) fs::remove(p, ec);
      continue;
    }
    if (p.extension() != ".lod" && p.extension() != ".lvl" && p.extension() != ".wall") continue;
    total += e.file_size(ec);
    files.emplace_back(t, p);
  }
  std::sort(files.begin(), files.end());
  for (const auto& [t, p] : files) {
    if (total <= kCacheBytes) break;
    const std::uintmax_t bytes = fs::file_size(p, ec);
    if (fs::remove(p, ec)) total -= bytes;
  }
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string check_nodes(const MeshClusters& c) {
  const std::size_t n = c.nodes.size(), indices = c.index_count();
  const auto in_indices = [&](std::uint64_t first, std::uint64_t count) {
    return count % 3 == 0 && first + count <= indices;
  };
  for (std::size_t k = 0; k < n; ++k) {
    const ClusterNode& node = c.nodes[k];
    const std::string at = fmt::format("node {}: ", k);
    if (!std::isfinite(node.error) || node.error < 0.0f || !finite(node.bounds.lo) ||
        !finite(node.bounds.hi))
      return at + "error or bounds not finite";
    if (!in_indices(node.mesh_first, node.mesh_count) ||
        !in_indices(node.leaf_first, node.leaf_count) ||
        std::uint64_t{node.leaf_first} + node.leaf_count > c.original_indices)
      return at + "a range outside the indices";
    if (node.levels_pending()) {
      if (node.levels_count != 0 || c.deferred_max_levels < 1 || c.deferred_max_levels > 64 ||
          (c.deferred_step != 2 && c.deferred_step != 4))
        return at + "pending levels without a way to build them";
    } else if (std::uint64_t{node.levels_first} + node.levels_count > c.levels.size()) {
      return at + "levels outside the list";
    }
    const bool leaf = node.children[0] < 0 && node.children[1] < 0;
    for (std::int32_t child : node.children)
      if (!leaf && (child <= static_cast<std::int64_t>(k) || static_cast<std::size_t>(child) >= n))
        return at + "a child out of order";
  }
  return "";
}

} // namespace

fs::path default_cache_folder() {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  if (xdg && *xdg && fs::path(xdg).is_absolute()) return fs::path(xdg) / "irad" / "hierarchy";
  const char* home = std::getenv("HOME");
  if (home && *home) return fs::path(home) / ".cache" / "irad" / "hierarchy";
  return {};
}

std::string ClusterKey::hex() const {
  return fmt::format("{:016x}{:016x}", high, low);
}

struct KeyHasher::State {
  HashState xxh{XXH3_createState()};
};

KeyHasher::KeyHasher() : state_(std::make_unique<State>()) {
  XXH3_128bits_reset(state_->xxh.get());
}
KeyHasher::~KeyHasher() = default;

void KeyHasher::add(const void* data, std::size_t n) {
  XXH3_128bits_update(state_->xxh.get(), data, n);
}

ClusterKey KeyHasher::key() const {
  const XXH128_hash_t h = XXH3_128bits_digest(state_->xxh.get());
  return {h.low64, h.high64};
}

ClusterKey cluster_key(const Scene& scene, const ClusterOptions& options) {
  KeyHasher hasher;
  const std::uint32_t leaf = options.leaf_triangles != 0
                                 ? options.leaf_triangles
                                 : automatic_leaf_triangles(scene.triangle_count());
  const std::array<std::uint32_t, 7> settings = {kClusterCacheFormat,
                                                 MESHOPTIMIZER_VERSION,
                                                 leaf,
                                                 options.simplify ? 1u : 0u,
                                                 static_cast<std::uint32_t>(options.max_levels),
                                                 options.camera ? 1u : 0u,
                                                 options.defer_levels ? 1u : 0u};
  hasher.add(settings.data(), sizeof settings);
  const float diagonal = scene.bounds.diagonal();
  hasher.add(&diagonal, sizeof diagonal);
  const std::uint64_t vertices = scene.positions.size();
  hasher.add(&vertices, sizeof vertices);
  hasher.add(scene.positions.data(), scene.positions.size() * sizeof(glm::vec3));
  if (options.camera) { // the weld reads every attribute, the trees the materials
    const auto add = [&](const auto& values, const char* name) {
      const std::uint64_t size = values.size();
      hasher.add(name, std::strlen(name));
      hasher.add(&size, sizeof size);
      hasher.add(values.data(), values.size() * sizeof(values[0]));
    };
    add(scene.normals, "normals");
    add(scene.uvs, "uvs");
    add(scene.uvs1, "uvs1");
    add(scene.colors, "colors");
    add(scene.tangents, "tangents");
  }
  // The opaque triangles as (index, a, b, c), and the camera's their material, in order.
  std::vector<std::uint32_t> chunk;
  for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
    if (scene.material_of(t).alpha_mode != AlphaMode::Opaque) continue;
    const glm::uvec3 v = scene.triangles[t];
    chunk.insert(chunk.end(), {static_cast<std::uint32_t>(t), v.x, v.y, v.z});
    if (options.camera) chunk.push_back(scene.triangle_material[t]);
    if (chunk.size() >= 4096) {
      hasher.add(chunk.data(), chunk.size() * sizeof(std::uint32_t));
      chunk.clear();
    }
  }
  hasher.add(chunk.data(), chunk.size() * sizeof(std::uint32_t));
  return hasher.key();
}

bool write_atomically(const fs::path& path, const std::function<bool(const fs::path&)>& write,
                      std::string& why) {
  const fs::path temporary =
      fmt::format("{}.tmp.{}.{}", path.string(), ::getpid(),
                  std::chrono::steady_clock::now().time_since_epoch().count());
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (!write(temporary)) {
    fs::remove(temporary, ec);
    why = fmt::format("cannot write {}", temporary.string());
    return false;
  }
  fs::rename(temporary, path, ec);
  if (ec) {
    fs::remove(temporary, ec);
    why = fmt::format("cannot write {}", path.string());
    return false;
  }
  return true;
}

const char* outcome_name(CacheOutcome outcome) {
  switch (outcome) {
  case CacheOutcome::Off:
    return "off";
  case CacheOutcome::Hit:
    return "hit";
  case CacheOutcome::Written:
    return "written";
  case CacheOutcome::Rebuilt:
    return "rebuilt";
  case CacheOutcome::Unwritable:
    return "unwritable";
  }
  return "?";
}

std::string validate_clusters(const MeshClusters& c, std::size_t vertices, std::size_t triangles,
                              std::size_t materials) {
  if (c.original_indices > c.index_count() || c.original_indices % 3 != 0)
    return "the original part exceeds the indices";
  for (std::uint32_t i : c.indices)
    if (i >= vertices) return "an index past the vertices";
  if (!below(c.late_indices.data(), c.late_indices.size(), vertices))
    return "a late index past the vertices";
  if (std::string why = check_nodes(c); !why.empty()) return why;
  for (const ClusterLevel& l : c.levels)
    if (!std::isfinite(l.error) || l.count % 3 != 0 ||
        std::uint64_t{l.first} + l.count > c.index_end())
      return "a level outside the indices";
  for (std::int32_t r : c.roots)
    if (r < 0 || static_cast<std::size_t>(r) >= c.nodes.size()) return "a root out of range";
  for (std::size_t k = 0; k < c.triangles.size(); ++k)
    if (c.triangles[k] >= triangles || (k > 0 && c.triangles[k] <= c.triangles[k - 1]))
      return "triangles not ascending or past the scene's";
  if (c.nodes.empty() != c.roots.empty()) return "roots without nodes";
  if (!c.root_materials.empty() && c.root_materials.size() != c.roots.size())
    return "root materials not one per root";
  for (std::uint32_t m : c.root_materials)
    if (m >= materials) return "a root material past the scene's";
  return "";
}

namespace {

// Writes c (its indices in memory) to `path` atomically and trims the folder: `out` becomes
// Written (a Rebuilt stays so) or Unwritable with the reason; "cache write" into `times`. Never
// throws.
void write_cache_file(const fs::path& path, const ClusterKey& key, const MeshClusters& c,
                      StageTimes* times, CacheResult& out) noexcept {
  const auto start = StageTimes::Clock::now();
  try {
    std::string why;
    if (!write_atomically(
            path, [&](const fs::path& to) { return write_file(to, c, key); }, why)) {
      out.set(CacheOutcome::Unwritable, why);
    } else {
      if (out.outcome == CacheOutcome::Off) out.outcome = CacheOutcome::Written;
      std::error_code ec; // late levels of an older file with this key: built again as needed
      fs::remove(late_levels_path(path), ec);
      trim_folder(path.parent_path());
    }
  } catch (const std::exception& e) { // memory, the file system
    out.set(CacheOutcome::Unwritable, e.what());
  }
  if (times) times->lap("cache write", start);
}

} // namespace

void PendingCacheWrite::run(StageTimes* times, CacheResult* result) noexcept {
  if (!pending()) return;
  CacheResult own;
  CacheResult& out = result ? *result : own;
  write_cache_file(path_, key_, hierarchy_, times, out);
  if (out.outcome != CacheOutcome::Unwritable) // the indices read from the file from now on
    leave_indices_in(path_, key_, vertices_, hierarchy_);
  hierarchy_ = {}; // the indices stay with their other user, or go
}

MeshClusters cached_mesh_clusters(const Scene& scene, const ClusterOptions& options,
                                  const fs::path& folder, StageTimes* times, CacheResult* result,
                                  PendingCacheWrite* later, const std::function<void()>& on_build) {
  CacheResult own;
  CacheResult& out = result ? *result : own;
  out = {};
  const auto build = [&](StageTimes* stages) {
    if (on_build) on_build();
    return build_mesh_clusters(scene, options, stages);
  };
  if (folder.empty()) return build(times);
  StageTimes local;
  StageTimes& stages = times ? *times : local;
  auto start = StageTimes::Clock::now();
  const ClusterKey key = cluster_key(scene, options);
  const fs::path path = folder / (key.hex() + ".lod");
  out.file = path;
  out.key = key;
  std::error_code ec;
  if (fs::exists(path, ec)) {
    std::string why;
    MeshClusters c = read_file(path, key, scene, why);
    if (why.empty()) out.late_nodes_read = read_late_levels(path, key, scene.positions.size(), c);
    stages.lap("cache read", start);
    if (why.empty()) {
      out.outcome = CacheOutcome::Hit;
      fs::last_write_time(path, fs::file_time_type::clock::now(), ec); // a use
      return c;
    }
    out.set(CacheOutcome::Rebuilt, why);
  }
  MeshClusters c = build(&stages);
  if (later) { // the indices shared between the hierarchy's user and the writer
    auto shared = std::make_shared<const std::vector<std::uint32_t>>(std::move(c.indices));
    c.indices = {};
    c.stored_indices = std::make_shared<const StoredIndices>(std::move(shared));
    later->hierarchy_ = c;
    later->path_ = path;
    later->key_ = key;
    later->vertices_ = scene.positions.size();
    return c;
  }
  write_cache_file(path, key, c, &stages, out);
  if (out.outcome != CacheOutcome::Unwritable)
    leave_indices_in(path, key, scene.positions.size(), c);
  return c;
}

} // namespace irad
