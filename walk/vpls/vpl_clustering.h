#pragma once
// The walk's VPLs as the representatives of their clusters (matrix row-column sampling:
// core/lights/light_clusters.h over the rows of walk/vpls/light_rows.h), what `--clusters` draws:
// rows weighted by their inverse totals, at most `clusters` clusters, one representative each, and
// the local clamp (core/lights/clamp_field.h) anew at the representatives' density.
#include "core/camera/view.h"
#include "core/lights/light_clusters.h"
#include "core/lights/vpl.h"
#include "core/scene/scene.h"
#include "walk/rays/ray_scene.h"

#include <atomic>
#include <cstdint>

namespace irad {

struct VplClusteringOptions {
  std::size_t clusters = 1024;
  std::size_t rows = 256;
  float clamp = 0.05f; // the global clamp (fraction of the diagonal): the local clamp's cap
  bool local_clamp = true;
  int clamp_neighbours = 8;
  // d = clamp_scale r_k at the representatives' density. Measured on the Cornell box at
  // 256x256, N = 8192 as 1024 clusters (4x4-block relMSE, seeds 1 and 3): 0.5 gives 6.4e-4 and
  // 1.1e-3 (the representatives' spikes), 1.0 5.3e-4 twice, 2.0-4.0 5.0-6.2e-4.
  float clamp_scale = 1.0f;
  std::uint64_t seed = 0;
  unsigned threads = 0;
  const std::atomic<bool>* cancel = nullptr;
};

Representatives cluster_vpls(const Scene& scene, const RayScene& rays, const View& view,
                             const VplSet& walk, const VplClusteringOptions& options);

} // namespace irad
