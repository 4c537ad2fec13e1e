#pragma once
// The thinnest-wall scan (walk/walls/thin_walls.h) kept on disk between runs, beside the shadow
// hierarchy (core/mesh/hierarchy/cluster_cache.h, the same folder and switch): the scan traces a
// ray per triangle (0.4 s on the 2.1M-triangle sphere box, 2 cores), reading its answer back a
// millisecond.
//
// A file per scene, FOLDER/<key>.wall, the key a 128-bit XXH3 hash of what the scan reads: the
// positions and triangles, the bounding diagonal and the ray epsilon, this format's version and
// Embree's. It holds the reach searched and the least gap found within it, so a later scan of
// the same or a shorter reach is answered from it; a longer one scans again and writes over it.
// Written atomically, never trusted: magic, version, key and an XXH3-64 checksum must match, the
// numbers be finite and in range; anything else is scanned again and written over.
//
// Scenes with Mask or Blend materials scan every run: their rays pass through textures' alpha,
// which the key does not hold.
#include "core/mesh/hierarchy/cluster_cache.h"
#include "walk/rays/ray_scene.h"

#include <filesystem>
#include <functional>

namespace irad {

// thinnest_wall(scene, rays, up_to) through the cache in `folder` (empty: off); `result` gets
// what the cache did. A cache that cannot be read or written is reported there, never thrown.
// `scan` answers where the cache cannot: thinnest_wall(scene, rays, up_to) by another road
// (walk/walls/wall_scan_ahead.h's shared rows); empty: thinnest_wall on all cores. What it throws
// passes through, and nothing is written.
float cached_thinnest_wall(const Scene& scene, const RayScene& rays, float up_to,
                           const std::filesystem::path& folder, CacheResult* result = nullptr,
                           const std::function<float()>& scan = {});

} // namespace irad
