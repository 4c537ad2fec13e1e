#pragma once
// irad bench: speed against error. For each scene it sweeps the number of paths N, the walk's
// point sequence and the estimator (raster, rt-vpl, pt with an spp sweep), times every stage and
// measures the error against a converged path-traced reference (cached on disk, its parameters
// in the file name). Rows go to CSV; plots are drawn by gnuplot.
#include "core/util/log.h"

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace irad::apps {

struct BenchOptions {
  bool quick = false; // a smoke run in well under 2 minutes
  std::string out_dir = "out/bench";
  std::string cornell = "data/cornell_box.gltf";
  // The third-party scenes zdm2 and godot (apps/bench/bench_real_scenes.h) are read from here.
  std::string shared = "../shared/scenes";
  // Any of cornell, cornell_glossy, sphere, large, sphere2m, zdm2, godot, godot_glossy (empty:
  // cornell, sphere, large).
  std::vector<std::string> scenes;
  int size = 0;                    // image side; 0: 64 quick, 256 full (zdm2, godot: 128)
  std::uint32_t reference_spp = 0; // 0: 256 quick, 4096 full (sphere2m: 1024)
  bool plots = true;
  bool scale = true; // the triangle-count study: OUT/scale.csv (never when only zdm2, godot run)
  bool scale_only = false; // only the triangle-count study
};

struct BenchRow {
  std::string scene;
  std::size_t triangles = 0;
  // raster, raster-k1 (interleave 1), rt-vpl: the local clamp and the screen-space
  // compensation, as `irad render`; raster-global: the global clamp, no compensation;
  // raster-clusters: the default raster over the cluster
  // representatives of the walk's VPLs (walk/vpls/vpl_clustering.h; `vpls` the walk's, `walk` the
  // walk and the clustering, vpls_per_second the walk's VPLs per second of the whole image);
  // raster-default and rt-vpl-default: `irad render`'s default (the light budget) through
  // lib/irad/render.h, with --estimator raster and rt-vpl, `rounds` light sets; pt
  std::string estimator;
  std::string sequence; // halton, scrambled-halton, random ("" for pt)
  std::uint32_t paths = 0, spp = 0;
  std::uint32_t rounds = 0; // raster-default, rt-vpl-default: --rounds (0: not such a row)
  std::size_t vpls = 0;
  int width = 0, height = 0;
  double load = 0, bvh = 0, walk = 0, shadow = -1, shading = -1, readback = 0, trace = 0, total = 0;
  double vpls_per_second = 0;
  double rmse = 0, relmse = 0, mean_ratio = 0;
  double relmse_block4 = 0; // relMSE of the 4x4-block means
  double compensation = 0;  // seconds of the screen-space compensation (in `total`)
  double peak_mib = 0; // the process's peak resident set during the row (apps/bench/peak_memory.h)
  // raster: the renderer's first render of one path before the rows (shaders, the shadow
  // cluster hierarchy), not in `total`: a set-up cost like `bvh`.
  double setup = 0;
};

// Runs the sweep, writes OUT/bench.csv (and plots), returns the rows. zdm2, godot and sphere2m
// run a smaller sweep (raster and rt-vpl with Halton only, N in {16, 64, 256}; pt up to 256
// spp, zdm2 and godot up to 1024); zdm2 and godot leave their lit copy in OUT (lit_NAME.gltf).
// The Cornell box, zdm2 and godot add the default (raster-default, rt-vpl-default) over rounds.
std::vector<BenchRow> run_bench(const BenchOptions& options, Log& log);

void write_bench_csv(const std::vector<BenchRow>& rows, const std::string& path);
// Walk and per-VPL raster/rt-vpl cost against the triangle count, 8k .. 2M triangles
// (apps/bench/bench_scale.cpp): the Cornell box split into 32 x 4^L triangles (flat walls) and the
// Cornell box with a sphere of as many triangles (curved), the raster with each
// RasterOptions::shadow_lod.
void run_scale_study(const BenchOptions& options, Log& log);
// The shadow level of detail's error on the real scenes among options.scenes (zdm2, godot):
// raster (interleave 1) with shadow-lod off, cull, on against rt-vpl with the same VPLs;
// OUT/shadow_lod_error.csv.
void run_shadow_lod_error(const BenchOptions& options, Log& log);
// error_vs_time.png (log-log, every estimator) and error_vs_paths.png (per sequence, with the
// least-squares slope of log relMSE against log N in the legend). Throws when gnuplot fails.
void write_bench_plots(const std::vector<BenchRow>& rows, const std::string& out_dir, Log& log);
// Least-squares slope of log(y) against log(x).
double loglog_slope(const std::vector<double>& x, const std::vector<double>& y);
// y at x on the log-log line through the two points of `curve` (x ascending, x and y > 0) whose
// x bracket it; nullopt outside the curve's x or with fewer than two points.
std::optional<double> loglog_at(const std::vector<std::pair<double, double>>& curve, double x);
// Every row against pt at its own time: pt's relMSE per pixel and per 4x4 block there (loglog_at
// over the scene's pt rows; rows outside pt's times are left out) and the ratios, as CSV; a log
// line for each row of the default over rounds (raster-default, rt-vpl-default).
void write_versus_pt(const std::vector<BenchRow>& rows, const std::string& path, Log& log);

} // namespace irad::apps
