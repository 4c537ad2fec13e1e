#pragma once
// The cluster hierarchies (core/mesh/hierarchy/mesh_clusters.h: the shadow passes', the camera's)
// kept on disk between runs: building it is the one-time cost of a big scene (seconds per million
// triangles), reading it back a fraction of that.
//
// A file per hierarchy, FOLDER/<key>.lod, the key a 128-bit XXH3 hash of everything the build
// reads: the positions, the opaque triangles (their indices and order), the scene's diagonal (the
// planar reduction's tolerance), for a camera hierarchy every vertex attribute and the
// triangles' materials, the resolved ClusterOptions (not the threads: the hierarchy is
// the same on any number), this file format's version and meshoptimizer's. Written atomically
// (a temporary file in the folder, renamed into place), so a reader sees a whole file or none.
//
// Never trusted: a file is used only when its magic, version, key and sizes match, its XXH3-64
// checksum over all it holds is right, and the hierarchy passes validate_clusters (every index
// names a vertex, every range lies inside its array, children after their parents); anything
// else (stale, foreign, truncated, bit-flipped) is rebuilt and written over. A hit checks the
// indices, the file's bulk, as they stream past and leaves them in the file
// (MeshClusters::stored_indices) for the GPU upload to copy. The folder is kept below kCacheBytes
// by removing the files least recently used.
#include "core/mesh/hierarchy/mesh_clusters.h"
#include "core/util/stage_times.h"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

namespace irad {

// $XDG_CACHE_HOME/irad/hierarchy, else $HOME/.cache/irad/hierarchy (XDG's default); empty when
// neither variable is set (no cache).
std::filesystem::path default_cache_folder();

struct ClusterKey {
  std::uint64_t low = 0, high = 0;
  std::string hex() const; // 32 hexadecimal digits, high first
  bool operator==(const ClusterKey&) const = default;
};

// A 128-bit XXH3 key of the bytes added in turn (cluster_key's; walk/walls/wall_cache.h's).
class KeyHasher {
public:
  KeyHasher();
  ~KeyHasher();
  KeyHasher(const KeyHasher&) = delete;
  KeyHasher& operator=(const KeyHasher&) = delete;
  void add(const void* data, std::size_t n);
  ClusterKey key() const;

private:
  struct State;
  std::unique_ptr<State> state_;
};

// The key of build_mesh_clusters(scene, options) (leaf_triangles 0 resolved as the build does).
ClusterKey cluster_key(const Scene& scene, const ClusterOptions& options);

// What the cache did for one hierarchy.
enum class CacheOutcome {
  Off,        // no folder: built, not written
  Hit,        // read back
  Written,    // not there: built and written
  Rebuilt,    // there but unusable (CacheResult::reason): built and written over
  Unwritable, // built; the folder or file could not be written (CacheResult::reason)
};
struct CacheResult {
  CacheOutcome outcome = CacheOutcome::Off;
  std::string reason; // why a file was not used, or could not be written
  // The hierarchy's file and key (empty with the cache off), for its late levels' file.
  std::filesystem::path file;
  ClusterKey key;
  std::size_t late_nodes_read = 0; // nodes whose late levels came from the late file
  void set(CacheOutcome o, std::string why) {
    outcome = o;
    reason = std::move(why);
  }
};
const char* outcome_name(CacheOutcome outcome); // "off", "hit", "written", "rebuilt", ...

// Checks what a reader must before it draws from c: every index in memory below `vertices`
// (stored ones are checked as the cache read streams them, and again when copied), every node's
// ranges inside `indices` and `levels`, children numbered after their parents, the leaves'
// ranges tiling [0, original_indices), roots in range, the triangles ascending and below
// `triangles`, a root material (if any) per root and below `materials`, errors and bounds
// finite. Returns what is wrong, or "" when nothing is.
std::string validate_clusters(const MeshClusters& c, std::size_t vertices, std::size_t triangles,
                              std::size_t materials);

// The cache file a build still has to write (cached_mesh_clusters with `later`), for a caller
// that hands the hierarchy on first and writes while it is in use.
class PendingCacheWrite {
public:
  bool pending() const { return !path_.empty() && hierarchy_.stored_indices != nullptr; }
  // Writes the file as cached_mesh_clusters would have (atomically, then the folder trimmed):
  // `result` becomes Written (a Rebuilt stays so) or Unwritable with the reason, `times` gets
  // "cache write". Once written, the indices handed on are read from the file
  // (StoredIndices::leave_in_file) and their memory goes. Then holds nothing. Never throws.
  void run(StageTimes* times, CacheResult* result) noexcept;

private:
  friend MeshClusters cached_mesh_clusters(const Scene&, const ClusterOptions&,
                                           const std::filesystem::path&, StageTimes*, CacheResult*,
                                           PendingCacheWrite*, const std::function<void()>&);
  std::filesystem::path path_;
  ClusterKey key_;
  std::size_t vertices_ = 0; // the scene's
  MeshClusters hierarchy_;   // its indices shared with the hierarchy handed on
};

// build_mesh_clusters through the cache in `folder` (empty: off). times gets the build's stages,
// or "cache read"; then "cache write" when it wrote. After a hit, and after a write, the
// indices are left in the file (MeshClusters::stored_indices); with the cache off, or a write
// that failed, they are in memory. With `later`, a build is returned before its file is written:
// its indices in memory, shared with *later, which writes the file when run (result's outcome is
// then Off, or Rebuilt, until it has). `on_build` (if given) is called once it is known that the
// hierarchy is built, not read (before the build). Throws only what the build throws: a cache
// that cannot be read or written is reported in `result`, never an error.
MeshClusters cached_mesh_clusters(const Scene& scene, const ClusterOptions& options,
                                  const std::filesystem::path& folder, StageTimes* times = nullptr,
                                  CacheResult* result = nullptr, PendingCacheWrite* later = nullptr,
                                  const std::function<void()>& on_build = {});

// Writes `path` through a temporary file beside it (write(temporary) returns whether every write
// succeeded) renamed into place, so that a reader sees a whole file or none; the folder is made
// first when missing. False, with `why`, when the temporary could not be written or renamed (the
// temporary is then removed).
bool write_atomically(const std::filesystem::path& path,
                      const std::function<bool(const std::filesystem::path&)>& write,
                      std::string& why);

// The most bytes the cache folder keeps: after a write, the least recently used files (a hit
// counts as a use) go until the rest fit.
inline constexpr std::uintmax_t kCacheBytes = std::uintmax_t{4} << 30;

} // namespace irad
