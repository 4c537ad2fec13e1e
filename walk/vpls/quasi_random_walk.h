#pragma once
// Keller's quasi-random walk (design.md section 1): N particles leave the lights, particle i
// reflects D(i) times (n_j = floor(rho_bar^j N) particles reach reflection j), and every vertex
// y_j of a path leaves a VPL of weight 1/n_j. Halton dimensions: (0, 1) start on a light,
// (2j+2, 2j+3) scatter at reflection j: cosine-distributed on a Lambertian surface, by the BRDF's
// sampler (core/material/brdf.h) elsewhere, the seed's "each surface decides by its BRDF".
// Particle i (i = 0..N-1, the index that decides its depth D(i)) takes Halton point x_{i+1}: the
// point x_0 = (0, 0, ...) is degenerate (a light's corner, then every bounce along the normal, so
// that path never leaves the scene) and, carrying the deepest terms alone, it biased the Cornell
// box high by 8 % at N = 256 (RMSE against the path tracer 0.043 with x_0, 0.010 without).
// Mirrors (seed section 5.1.2, core/scene/mirrors.h): a particle reflects in every mirror it meets
// on its way to the next diffuse surface (beta *= R each time; not counted as a reflection j, since
// n_j counts diffuse events and the specular bounce is deterministic), and every VPL is followed
// in the list by its mirrored copies, which keep its path index.
#include "core/lights/light_sampler.h"
#include "core/lights/vpl.h"
#include "core/sampling/particle_counts.h"
#include "core/sampling/sequence.h"
#include "core/scene/mirrors.h"
#include "core/scene/scene.h"
#include "core/util/log.h"
#include "walk/rays/ray_scene.h"

#include <cstdint>
#include <vector>

namespace irad {

// Halton index of particle i.
constexpr std::uint32_t halton_index(std::uint32_t particle) {
  return particle + 1;
}

struct WalkOptions {
  std::uint32_t paths = 256; // N
  // l_max is capped here; it binds only when rho_bar is close to 1 (then a warning is logged).
  int depth_cap = 64;
  SequenceKind sequence = SequenceKind::Halton; // design.md: Halton
  std::uint64_t seed = 0;                       // scrambled-halton and random only
  // How the N paths are shared among the lights (core/lights/light_sampler.h): by power
  // (design.md 6.2) or N/G per light; the light is chosen from the walk's first, best stratified
  // dimension.
  LightAllocation allocation = LightAllocation::Power;
  // Trace only the particles first_path..end_path-1 (end_path 0: N) of the N-path walk: the same
  // VPLs with the same weights 1/n_j as the full walk, so the images of disjoint ranges add up to
  // the full image (irad render --path-range, irad merge).
  std::uint32_t first_path = 0;
  std::uint32_t end_path = 0;
};

struct PathVertex; // a surface the particle meets (quasi_random_walk.cpp)

// The walk for a fixed scene and N: particles can be traced one at a time (the real-time ring of
// section 5.1.3 traces one path per frame). Throws irad::Error when the scene has no light or the
// options are impossible. Holds references to the scene and rays.
class QuasiRandomWalk {
public:
  QuasiRandomWalk(const Scene& scene, const RayScene& rays, const WalkOptions& options, Log& log);
  // Appends particle i's VPLs (depths 0..D(i), fewer if it leaves the scene or is absorbed), and
  // the lobes of its glossy VPLs to *lobes (core/lights/vpl.h; null: the VPLs keep lobe -1 and
  // their Lambertian intensity: every estimator then draws them as Lambertian VPLs).
  void trace(std::uint32_t i, std::vector<Vpl>& out, std::vector<VplLobe>* lobes = nullptr) const;
  // N, rho_bar, l_max, ... with no VPLs.
  VplSet header() const;
  const ParticleCounts& counts() const { return counts_; }

private:
  // The VPL at a glossy vertex y_j and the particle's next direction and throughput; false when
  // the path ends there.
  bool glossy_vertex(const PathVertex& y, std::uint32_t i, int j, int depth, glm::vec3& beta,
                     glm::vec3& dir, std::vector<Vpl>& out, std::vector<VplLobe>* lobes) const;

  const Scene* scene_;
  const RayScene* rays_;
  LightSampler lights_;
  ParticleCounts counts_;
  Sequence halton_;
  std::vector<MirrorPolygon> mirrors_; // core/scene/mirrors.h; empty: the diffuse walk unchanged
};

// All N particles (or the range of WalkOptions). Throws irad::Error when the scene has no light or
// the options are impossible.
VplSet quasi_random_walk(const Scene& scene, const RayScene& rays, const WalkOptions& options,
                         Log& log);

} // namespace irad
