#pragma once
// Keller's quasi-random walk (design.md section 1): N particles leave the lights, particle i
// reflects D(i) times (n_j = floor(rho_bar^j N) particles reach reflection j), and every vertex
// y_j of a path leaves a VPL of weight 1/n_j. Halton dimensions: (0, 1) start on a light,
// (2j+2, 2j+3) scatter at reflection j (cosine-distributed).
#include "core/log.h"
#include "core/scene.h"
#include "core/vpl.h"
#include "walk/ray_scene.h"

#include <cstdint>

namespace irad {

struct WalkOptions {
  std::uint32_t paths = 256; // N
  // l_max is capped here; it binds only when rho_bar is close to 1 (then a warning is logged).
  int depth_cap = 64;
};

// Throws irad::Error when the scene has no light or the options are impossible.
VplSet quasi_random_walk(const Scene& scene, const RayScene& rays, const WalkOptions& options,
                         Log& log);

} // namespace irad
