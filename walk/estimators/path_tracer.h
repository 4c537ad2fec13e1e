#pragma once
// The converged reference ("pt"): a unidirectional path tracer for the same scene model (the glTF
// BRDF of core/material/brdf.h, Lambertian emitters, punctual lights), independent of the walk's
// estimator. Camera rays go through pixel centres (the raster's sampling), so the two integrate
// the same function. Next-event estimation toward emitters (chosen by power) and BRDF sampling
// (cosine-weighted on a Lambertian material; elsewhere visible-normal GGX or the cosine lobe, one
// per sample, chosen by the specular lobe's share of the directional albedo, with the mixture's
// pdf) are combined with multiple importance sampling (power heuristic); punctual lights (point,
// spot, directional: delta lights) are reached by next-event estimation only, without MIS weight.
// The environment (core/environment/environment.h) is sampled by its luminance density as one
// more light and weighted against BRDF sampling, which finds it when a scattered ray leaves the
// scene; a camera ray that leaves shows core/scene/scene.h background_radiance (0 when the
// environment is not visible). Russian roulette after three bounces. No clamp: unbiased. Mirrors
// (Material::specular) reflect perfectly: no next-event estimation there, and an emitter found
// right after a mirror counts with weight 1 (light samples cannot reach it through the mirror). So
// light that reaches a non-mirror point by way of a mirror is found by scattering only (noisier),
// and a punctual light seen through a mirror is never found (delta light and delta mirror):
// compare mirror scenes with area lights only. Deterministic for a given seed whatever the thread
// count (one RNG stream per pixel and sample).
#include "core/camera/view.h"
#include "core/image/image.h"
#include "core/scene/scene.h"
#include "walk/rays/ray_scene.h"

#include <atomic>
#include <cstdint>
#include <functional>

namespace irad {

struct PathTracerOptions {
  std::uint32_t spp = 64; // samples per pixel
  std::uint64_t seed = 0;
  unsigned threads = 0; // 0: hardware concurrency
  int max_depth = 1000; // bounces (Russian roulette ends paths long before)
  // false: every camera ray through the pixel centre (the raster's sampling without jitter);
  // true: each sample through a uniform point of the pixel (box filter: the antialiased image
  // the raster's --jitter converges to).
  bool pixel_footprint = false;
  // When it becomes true (a signal handler), no further pixel is started: those left are 0,
  // alpha included.
  const std::atomic<bool>* cancel = nullptr;
  // Last, so that aggregate initialisations of the fields above stay as they were.
  // Trace only samples first_sample..end_sample-1 (end_sample 0: spp) of every pixel, the same
  // samples as the full run, divided by spp all the same; alpha is their share (end - first)/spp.
  // The images of disjoint ranges add up to the full image (irad render --spp-range).
  std::uint32_t first_sample = 0;
  std::uint32_t end_sample = 0;
};

Image path_trace(const Scene& scene, const RayScene& rays, const View& view,
                 const PathTracerOptions& options,
                 const std::function<void(int rows_done, int rows)>& progress = {});

} // namespace irad
