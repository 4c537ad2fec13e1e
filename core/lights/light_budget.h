#pragma once
// The automatic light budget, `irad render`'s default (`--paths auto --clusters auto`): how many
// light paths N to walk and how many cluster representatives (core/lights/light_clusters.h) to
// draw, so that a render's cost follows the number of VPLs the scene's walk leaves, not a fixed N.
//   paths: a pilot walk of `pilot_paths` leaves V_p VPLs; N is the largest power of two with
//          N V_p / pilot_paths <= vpls (at least min_paths, at most max_paths). The walk is
//          deterministic, so every render of a scene and its options chooses the same N.
//   clusters: a walk of V VPLs is drawn as clamp(V / vpls_per_cluster, min_clusters,
//          max_clusters) representatives when V exceeds min_clusters * vpls_per_cluster, else
//          as every VPL (0: no clustering). The ratio 16 and the cap 2048 are measured on the
//          Cornell box at 256x256 (docs/performance.md "Error against time with cluster
//          representatives": one cluster per 16 VPLs holds the error of all 30570 VPLs at N =
//          16384; past 2048 clusters the 4x4-block error stops falling).
#include <cstddef>
#include <cstdint>

namespace irad {

struct LightBudget {
  std::size_t vpls = 32768; // the walk's VPLs aimed at
  std::uint32_t pilot_paths = 256;
  std::uint32_t min_paths = 256;
  std::uint32_t max_paths = 65536;
  std::size_t vpls_per_cluster = 16;
  std::size_t min_clusters = 256;
  std::size_t max_clusters = 2048;
};

// N for a scene whose first `budget.pilot_paths` paths left `pilot_vpls` VPLs.
std::uint32_t budget_paths(std::size_t pilot_vpls, const LightBudget& budget);

// The representatives for a walk of `vpls` VPLs; 0: draw every VPL.
std::size_t budget_clusters(std::size_t vpls, const LightBudget& budget);

// The shadow faces' resolution for cluster representatives in a width x height image rendered as
// the mean of `rounds` light sets, given the raster's rule for every VPL (`rule`,
// raster/raster_renderer.h shadow_resolution_for): the rule below 4 rounds or where the unsure
// pixels are traced (`traced`: trace_edge_pixels below, with interleaving), else at least half
// the image's larger side up to 128 texels (the .cpp has the measurements).
int representative_shadow_resolution(int rule, int width, int height, unsigned rounds, bool traced);

// Whether the raster's edge and unsure pixels (raster/raster_renderer.h EdgePixelMode Listed) are
// traced over the same cluster representatives when `rounds` light sets are averaged: from 2
// rounds on, where the representatives' noise is low enough to show what the shadow maps and the
// interleaved filter get wrong at creases, contacts and silhouettes (the .cpp has the
// measurements). One round, the quick look, keeps the raster's speed.
bool trace_edge_pixels(unsigned rounds);

} // namespace irad
