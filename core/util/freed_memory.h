#pragma once
// How the process's big arrays meet the kernel's pages: freed heap handed back, fresh arrays
// backed by huge pages.
#include <cstddef>
#include <type_traits>
#include <vector>

namespace irad {

// Hands the heap's free pages back to the system (glibc's malloc_trim; nothing elsewhere). Where
// the process keeps freed heap for speed (apps/main.cpp keeps up to 128 MiB at its top), the holes
// a one-time stage leaves (the loader's arrays, the BVH builder's) would otherwise stay resident
// for the whole render; a stage calls this when its transients are gone.
void release_freed_memory();

// Whether the kernel may back the heap with transparent huge pages: THPeligible of the first
// [heap] mapping in /proc/self/smaps (apps/main.cpp has glibc advise it). false where unreadable,
// where the process has no heap yet, or off Linux.
bool heap_huge_pages();

// Asks the kernel to back the 2 MiB-aligned pages inside [data, data + bytes) with transparent
// huge pages (madvise MADV_HUGEPAGE: the kernel's "madvise" mode), before they are first
// written: a big array then costs one page fault and one clear per 2 MiB instead of per 4 KiB.
// Nothing for less than 4 MiB, off Linux, or where the kernel refuses.
void advise_huge_pages(const void* data, std::size_t bytes);

// Writes a byte of every page of [data, data + bytes) on all cores, so that the kernel gives
// and clears the pages of fresh storage in parallel before a loop on one thread (a vector's
// resize, a file's read) writes it: on this machine a fresh page costs ten times writing it
// (0.4 ms per MiB of 4 KiB pages against 0.04 ms to write them again). Nothing for less than
// 4 MiB. The bytes written are the caller's to overwrite.
void touch_pages(void* data, std::size_t bytes);

// v.reserve(n), its new storage advised as above and its pages touched (touch_pages).
template <class T>
void reserve_huge(std::vector<T>& v, std::size_t n) {
  static_assert(std::is_trivially_copyable_v<T>, "touch_pages writes bytes into the new storage");
  if (n <= v.capacity()) return;
  v.reserve(n);
  advise_huge_pages(v.data(), v.capacity() * sizeof(T));
  touch_pages(v.data() + v.size(), (v.capacity() - v.size()) * sizeof(T));
}

// v.resize(n), its new storage advised as above.
template <class T>
void resize_huge(std::vector<T>& v, std::size_t n) {
  reserve_huge(v, n);
  v.resize(n);
}

} // namespace irad
