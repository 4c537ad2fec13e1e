#pragma once
// The shadow hierarchy's indices where they lie: in memory shared with the cache's writer (a build
// handed on before its file is written: core/mesh/hierarchy/background_clusters.h) until the file
// is written, or in its cache file (core/mesh/hierarchy/cluster_cache.h): a hit checks them as it
// streams the file (checksum, every index below the vertex count) but keeps none of them; the one
// reader that needs them, the GPU buffer (raster/shadow/shadow_lod.h), copies the parts the shadow
// faces draw from the file straight into its storage. After a hit, and once a build's file is
// written, the process holds none of them (docs/performance.md "Big scenes").
//
// The file stays open from the check to the last copy, so a writer that renames another file into
// its place, or a trim that removes it, leaves this one readable as it was. Only a change of the
// file in place (never irad's: it writes atomically) can make a copy differ from what was
// checked: every copy checks its indices again and throws then.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <vector>

namespace irad {

// A file open for reading at any offset from any thread (pread); closed with its last owner.
class OpenFile {
public:
  // valid() is false when `path` cannot be opened.
  explicit OpenFile(const std::filesystem::path& path);
  ~OpenFile();
  OpenFile(const OpenFile&) = delete;
  OpenFile& operator=(const OpenFile&) = delete;

  bool valid() const { return fd_ >= 0; }
  const std::filesystem::path& path() const { return path_; }
  // Its size in bytes now (0 when it cannot be told).
  std::uint64_t size() const;
  // Reads bytes [offset, offset + n) into out; false when the file ends before or a read fails.
  bool read_at(void* out, std::size_t n, std::uint64_t offset) const;

private:
  int fd_ = -1;
  std::filesystem::path path_;
};

class StoredIndices {
public:
  // `count` 32-bit indices from byte `offset` of `file`, each below `vertices` when checked.
  StoredIndices(std::shared_ptr<const OpenFile> file, std::uint64_t offset, std::size_t count,
                std::size_t vertices)
      : source_{std::move(file), nullptr, offset, vertices}, count_(count) {}
  // Indices a build made, shared with whoever else reads them (checked by the build).
  explicit StoredIndices(std::shared_ptr<const std::vector<std::uint32_t>> memory)
      : count_(memory->size()) {
    source_.memory = std::move(memory);
  }

  std::size_t size() const { return count_; }
  // Copies indices [first, first + count) (within size()) into out[0, count). Throws Error
  // (naming the file) when a read comes short or an index is not below the vertex count: the
  // file changed after it was checked.
  void copy_range(std::size_t first, std::size_t count, std::uint32_t* out) const;
  // All of them, copied as above.
  std::vector<std::uint32_t> read() const;
  // The indices when they are in memory; nullptr when in a file.
  std::shared_ptr<const std::vector<std::uint32_t>> in_memory() const;
  // Indices in memory, once written to `file` from byte `offset`: later copies read them from
  // there (checked against `vertices` as a hit's are) and the memory is freed with its last
  // user (a copy under way keeps it), so that a build's render holds no more of them than a
  // warm one. Nothing when they are in a file already.
  void leave_in_file(std::shared_ptr<const OpenFile> file, std::uint64_t offset,
                     std::size_t vertices) const;

private:
  // Where the indices are: memory, or a file from `offset` (a build's move to its file once
  // written: leave_in_file). Read and changed under `mutex`.
  struct Source {
    std::shared_ptr<const OpenFile> file;
    std::shared_ptr<const std::vector<std::uint32_t>> memory;
    std::uint64_t offset = 0;
    std::size_t vertices = 0;
  };
  Source source() const;

  mutable std::mutex mutex_;
  mutable Source source_;
  std::size_t count_ = 0;
};

// Whether the `count` indices in `words` are all below `vertices`.
bool below(const std::uint32_t* words, std::size_t count, std::size_t vertices);

} // namespace irad
