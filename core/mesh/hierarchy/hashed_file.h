#pragma once
// What the cache files of the shadow hierarchy share (core/mesh/hierarchy/cluster_cache.h: the
// hierarchy's file and its late levels' file, late_levels_file.h): their layout's version, 32-bit
// words of any 4-byte value, and a writer and a reader that hash all they pass (XXH3-64) and
// check the checksum at the end. Internal to core/mesh/hierarchy.
#include "core/mesh/hierarchy/stored_indices.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <vector>
#include <xxhash.h>

namespace irad::cache_io {

// The files' layout version: raise it whenever a layout or the build's results change.
inline constexpr std::uint32_t kClusterCacheFormat = 14;

template <class T>
std::uint32_t word(T value) {
  static_assert(sizeof(T) == 4);
  std::uint32_t w;
  std::memcpy(&w, &value, 4);
  return w;
}
template <class T>
T from_word(std::uint32_t w) {
  static_assert(sizeof(T) == 4);
  T value;
  std::memcpy(&value, &w, 4);
  return value;
}

struct FreeHashState {
  void operator()(XXH3_state_t* s) const { XXH3_freeState(s); }
};
using HashState = std::unique_ptr<XXH3_state_t, FreeHashState>;

// Bytes written through a running XXH3-64 checksum.
class HashedWriter {
public:
  explicit HashedWriter(const std::filesystem::path& path)
      : out_(path, std::ios::binary | std::ios::trunc) {
    XXH3_64bits_reset(state_.get());
  }
  void bytes(const void* data, std::size_t n) {
    XXH3_64bits_update(state_.get(), data, n);
    out_.write(static_cast<const char*>(data), static_cast<std::streamsize>(n));
  }
  template <class T>
  void values(const std::vector<T>& v) {
    bytes(v.data(), v.size() * sizeof(T));
  }
  // The checksum of everything so far, appended (not hashed); whether every write succeeded.
  bool finish() {
    const std::uint64_t sum = XXH3_64bits_digest(state_.get());
    out_.write(reinterpret_cast<const char*>(&sum), sizeof sum);
    out_.close();
    return static_cast<bool>(out_);
  }

private:
  std::ofstream out_;
  HashState state_{XXH3_createState()};
};

// Reads what HashedWriter wrote, hashing as it goes; any short read leaves it failed.
class HashedReader {
public:
  explicit HashedReader(std::shared_ptr<const OpenFile> file) : file_(std::move(file)) {
    XXH3_64bits_reset(state_.get());
  }
  std::uint64_t offset() const { return offset_; }
  bool bytes(void* data, std::size_t n) {
    ok_ = ok_ && file_->read_at(data, n, offset_);
    if (!ok_) return false;
    offset_ += n;
    XXH3_64bits_update(state_.get(), data, n);
    return true;
  }
  template <class T>
  bool values(std::vector<T>& v, std::size_t n) {
    v.resize(n);
    return bytes(v.data(), n * sizeof(T));
  }
  // Hashes `n` 32-bit indices through a small buffer, keeping none; all_below: whether every
  // one is below `vertices`.
  bool indices(std::size_t n, std::size_t vertices, bool& all_below) {
    all_below = true;
    std::vector<std::uint32_t> chunk(std::min<std::size_t>(n, std::size_t{1} << 18));
    for (std::size_t done = 0; done < n;) {
      const std::size_t k = std::min(chunk.size(), n - done);
      if (!bytes(chunk.data(), k * sizeof(std::uint32_t))) return false;
      all_below = all_below && below(chunk.data(), k, vertices);
      done += k;
    }
    return true;
  }
  // Whether the stored checksum follows and matches (the caller checked the file's size).
  bool checksum_matches() {
    std::uint64_t stored = 0;
    return ok_ && file_->read_at(&stored, sizeof stored, offset_) &&
           stored == XXH3_64bits_digest(state_.get());
  }

private:
  std::shared_ptr<const OpenFile> file_;
  std::uint64_t offset_ = 0;
  bool ok_ = true;
  HashState state_{XXH3_createState()};
};

} // namespace irad::cache_io
