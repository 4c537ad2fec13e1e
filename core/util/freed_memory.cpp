#include "core/util/freed_memory.h"

#include "core/util/parallel_rows.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <string>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace irad {

void release_freed_memory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

bool heap_huge_pages() {
  std::ifstream smaps("/proc/self/smaps");
  bool in_heap = false;
  for (std::string line; std::getline(smaps, line);) {
    // A mapping's first line: "start-end perms offset dev inode [path]", its path last.
    const bool header = !line.empty() && std::isxdigit(static_cast<unsigned char>(line[0])) &&
                        line.find('-') < line.find(' ');
    if (header) {
      in_heap = line.size() >= 6 && line.compare(line.size() - 6, 6, "[heap]") == 0;
    } else if (in_heap && line.rfind("THPeligible:", 0) == 0) {
      return line.find('1') != std::string::npos;
    }
  }
  return false;
}

void advise_huge_pages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
  if (bytes < 2 * kHuge) return;
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t last = (begin + bytes) & ~(kHuge - 1);
  if (last > first)
    madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE); // advice: may fail
#else
  (void)data;
  (void)bytes;
#endif
}

void touch_pages(void* data, std::size_t bytes) {
  constexpr std::size_t kPage = 4096;
  if (bytes < (std::size_t{4} << 20)) return;
  // Handed out a huge page (512 small ones) at a time: parallel_chunks's chunks of 2^16
  // elements would give an array below 256 MiB of pages to one thread.
  constexpr std::size_t kBlock = 512;
  auto* first = static_cast<unsigned char*>(data);
  const std::size_t pages = (bytes + kPage - 1) / kPage;
  const auto blocks = static_cast<int>((pages + kBlock - 1) / kBlock);
  parallel_rows(blocks, 0, [&](int b) {
    const std::size_t begin = static_cast<std::size_t>(b) * kBlock;
    for (std::size_t p = begin; p < std::min(pages, begin + kBlock); ++p) first[p * kPage] = 0;
  });
}

} // namespace irad
