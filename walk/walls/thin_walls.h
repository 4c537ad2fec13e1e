#pragma once
// The thinnest wall of a scene, for the raster's choice of occluder planes (raster/glsl/
// cube_glsl.h; RasterOptions::shadow_lod.planes = Auto): a shadow texel's centre distance alone
// lets a receiver through only where it lies less than about a texel's depth range behind an
// occluder's plane (raster_renderer.h planes_needed), as the floor beside a thin wall's foot on
// the wall's dark side does.
//
// A wall is two faces turned back to back: from the centroid of a one-sided triangle A, the
// first surface behind A (along -n_A) that turns its back to A, at the gap g between them (0 for
// coincident faces of opposite winding). A double-sided or mirror surface is a wall of thickness
// 0 by itself. Not counted as walls: one-sided faces with nothing behind them (glTF culls them
// seen from behind, so nothing lies on their dark side), and a surface behind A that faces A's
// back (a panel under a ceiling: what lies behind the panel is hidden by it from every point in
// front of it).
#include "core/scene/scene.h"
#include "walk/rays/ray_scene.h"

#include <atomic>

namespace irad {

// Whether some opaque triangle is double-sided or a mirror: a wall of thickness 0 by itself.
bool has_zero_wall(const Scene& scene);

// The thinnest wall's thickness as a fraction of the bounding diagonal, looked for up to
// `up_to` (a fraction too); `up_to` itself when there is none that thin. One ray per opaque
// one-sided triangle (from just in front of its centroid, through the triangle itself; two where
// a face lies on its plane), on `threads` threads (0: all cores); 0 at once when some opaque
// triangle is double-sided or a mirror.
float thinnest_wall(const Scene& scene, const RayScene& rays, float up_to, unsigned threads = 0);

// thinnest_wall's scan as rows that any threads take in turn, each joining when it likes: a scan
// begun ahead of its need on one thread of the lowest priority (walk/walls/wall_scan_ahead.h) is
// finished by every core once the answer is wanted. The answer is the same whichever threads
// took which rows. The scene and the rays must outlive it.
class WallScan {
public:
  WallScan(const Scene& scene, const RayScene& rays, float up_to);
  WallScan(const WallScan&) = delete;
  WallScan& operator=(const WallScan&) = delete;

  // Scans rows until none is left to take or `stop` is set; returns once this thread's rows are
  // done.
  void work(const std::atomic<bool>* stop = nullptr);
  // Rows of the scan (0 where the answer needs no ray).
  int rows() const { return rows_; }
  // Whether every row was scanned; false for good once a stop dropped a row.
  bool complete() const { return done_.load() == rows_; }
  // thinnest_wall's answer; complete() must hold.
  float result() const;

private:
  const Scene& scene_;
  const RayScene& rays_;
  float up_to_ = 0.0f, diagonal_ = 0.0f;
  bool zero_wall_ = false; // has_zero_wall: 0 without a ray
  int rows_ = 0;
  std::atomic<int> next_{0}, done_{0};
  // The least gap so far (scene units), shared by the rows: each row's rays reach only as far as
  // it, which is exact (a gap beyond the least found cannot be the least) and shortens the rays
  // after the first walls.
  std::atomic<float> least_{0.0f};
};

} // namespace irad
