#include "core/mesh/hierarchy/stored_indices.h"

#include "core/util/error.h"

#include <algorithm>
#include <cerrno>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace irad {

OpenFile::OpenFile(const std::filesystem::path& path)
    : fd_(::open(path.c_str(), O_RDONLY | O_CLOEXEC)), path_(path) {}

OpenFile::~OpenFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::uint64_t OpenFile::size() const {
  struct stat st {};
  if (fd_ < 0 || ::fstat(fd_, &st) != 0 || st.st_size < 0) return 0;
  return static_cast<std::uint64_t>(st.st_size);
}

bool OpenFile::read_at(void* out, std::size_t n, std::uint64_t offset) const {
  auto* p = static_cast<char*>(out);
  while (n > 0) {
    const ssize_t got = ::pread(fd_, p, n, static_cast<off_t>(offset));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    p += got;
    n -= static_cast<std::size_t>(got);
    offset += static_cast<std::uint64_t>(got);
  }
  return true;
}

bool below(const std::uint32_t* words, std::size_t count, std::size_t vertices) {
  std::uint32_t largest = 0;
  for (std::size_t k = 0; k < count; ++k) largest = std::max(largest, words[k]);
  return count == 0 || largest < vertices;
}

StoredIndices::Source StoredIndices::source() const {
  const std::lock_guard lock(mutex_);
  return source_;
}

std::shared_ptr<const std::vector<std::uint32_t>> StoredIndices::in_memory() const {
  return source().memory;
}

void StoredIndices::leave_in_file(std::shared_ptr<const OpenFile> file, std::uint64_t offset,
                                  std::size_t vertices) const {
  std::shared_ptr<const std::vector<std::uint32_t>> memory; // freed after the lock, if last
  const std::lock_guard lock(mutex_);
  if (!source_.memory) return;
  memory = std::move(source_.memory);
  source_ = {std::move(file), nullptr, offset, vertices};
}

void StoredIndices::copy_range(std::size_t first, std::size_t count, std::uint32_t* out) const {
  const Source s = source(); // a copy: a move to the file meanwhile leaves it whole
  if (first > count_ || count > count_ - first)
    throw Error(s.file ? s.file->path().string() : std::string(), "cluster hierarchy",
                "indices read past their end");
  if (s.memory) {
    std::copy_n(s.memory->begin() + static_cast<std::ptrdiff_t>(first), count, out);
    return;
  }
  if (!s.file->read_at(out, count * sizeof(std::uint32_t),
                       s.offset + first * sizeof(std::uint32_t)) ||
      !below(out, count, s.vertices))
    throw Error(s.file->path().string(), "cluster hierarchy",
                "the cache file changed while in use; remove it and render again");
}

std::vector<std::uint32_t> StoredIndices::read() const {
  std::vector<std::uint32_t> v(count_);
  copy_range(0, count_, v.data());
  return v;
}

} // namespace irad
