#pragma once
// The levels a render built after the shadow hierarchy (MeshClusters::late_nodes, late_indices:
// the shadow passes build deferred levels as faces first need them, raster/shadow/shadow_lod.h),
// kept beside the hierarchy's cache file (core/mesh/hierarchy/cluster_cache.h), FILE.lvl for
// FILE.lod, so that the next render of the scene draws them without building them again.
//
// Written atomically, all of them (those read and those built since); read after a hit and
// merged only when its magic, versions, key, the hierarchy's sizes and its checksum match, each
// of its nodes is pending in the hierarchy, its levels lie in its indices, their errors are
// finite and at least their node's, and every index names a vertex: anything else is ignored
// (its levels are built again where needed, and the file written over). Neither throws.
#include "core/mesh/hierarchy/cluster_cache.h"
#include "core/mesh/hierarchy/mesh_clusters.h"

#include <cstddef>
#include <filesystem>
#include <string>

namespace irad {

// The late levels' file of the hierarchy file `file`.
std::filesystem::path late_levels_path(const std::filesystem::path& file);

// Merges the late levels kept for the hierarchy c read from `file` under `key` (c has none yet);
// returns the nodes it gave levels (0: none kept, or a file not trusted).
std::size_t read_late_levels(const std::filesystem::path& file, const ClusterKey& key,
                             std::size_t vertices, MeshClusters& c) noexcept;
// Writes c's late levels beside `file`; false, with `why`, where it could not.
bool write_late_levels(const std::filesystem::path& file, const ClusterKey& key,
                       const MeshClusters& c, std::string& why) noexcept;

} // namespace irad
