#pragma once
// Hands the heap's free pages back to the system (glibc's malloc_trim; nothing elsewhere). Where
// the process keeps freed heap for speed (apps/main.cpp keeps up to 128 MiB at its top), the holes
// a one-time stage leaves (the loader's arrays, the BVH builder's) would otherwise stay resident
// for the whole render; a stage calls this when its transients are gone.
namespace irad {

void release_freed_memory();

} // namespace irad
