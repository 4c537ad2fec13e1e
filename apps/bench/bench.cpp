#include "apps/bench/bench.h"
#include "apps/bench/bench_real_scenes.h"
#include "apps/bench/peak_memory.h"
#include "apps/bench/stopwatch.h"

#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/image/image_io.h"
#include "core/image/image_metrics.h"
#include "core/lights/clamp_field.h"
#include "core/mesh/sphere_mesh.h"
#include "core/scene/analytic_scenes.h"
#include "core/scene/scene_builder.h"
#include "core/util/error.h"
#include "irad/render.h"
#include "raster/raster_renderer.h"
#include "walk/compensation/screen_compensation.h"
#include "walk/estimators/path_tracer.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/vpls/quasi_random_walk.h"
#include "walk/vpls/vpl_clustering.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>

namespace irad::apps {

namespace {

struct Sweep {
  int size;
  std::uint32_t reference_spp;
  std::vector<std::uint32_t> paths;              // raster, every sequence
  std::vector<std::uint32_t> rt_paths;           // rt-vpl, Halton
  std::vector<std::uint32_t> spp;                // pt
  int large_levels;                              // 32 * 4^levels triangles
  bool every_sequence = true;                    // raster: every sequence (false: Halton only)
  std::uint32_t raster_max = ~0u;                // raster: only the N up to this
  std::uint32_t k1_max = ~0u;                    // raster-k1: only the N up to this
  std::vector<std::uint32_t> cluster_paths = {}; // raster-clusters (walk/vpls/vpl_clustering.h)
  // raster-default and rt-vpl-default: `irad render`'s default with --rounds M for each M here
  // (rt-vpl only up to rt_rounds_max), the error against time past one light set.
  std::vector<std::uint32_t> rounds = {1};
  std::uint32_t rt_rounds_max = ~0u;
};

// The sweep of scene `name`. Real scenes (58k-64k triangles): every raster pass draws all of
// them on llvmpipe, so they take a smaller image, fewer N and a cheaper reference.
Sweep sweep_for(const BenchOptions& o, const std::string& name) {
  Sweep s =
      o.quick
          ? Sweep{64, 256, {16, 64}, {16}, {4, 16}, 7}
          : Sweep{
                256, 4096, {16, 32, 64, 128, 256, 512, 1024}, {16, 64, 256}, {4, 16, 64, 256, 1024},
                7};
  if (name == "large") s.raster_max = o.quick ? 16u : 64u;
  if (name == "cornell" && !o.quick) { // up to ~30 s, where pt meets the raster
    s.paths.insert(s.paths.end(), {4096, 16384});
    s.rt_paths.insert(s.rt_paths.end(), {1024, 4096});
    s.k1_max = 4096;
  }
  if (name == "cornell_glossy") { // the default's error against time, and the estimators'
    s.paths = o.quick ? std::vector<std::uint32_t>{16} : std::vector<std::uint32_t>{64, 256, 1024};
    s.rt_paths = o.quick ? std::vector<std::uint32_t>{16} : std::vector<std::uint32_t>{256, 1024};
    s.every_sequence = false;
    s.k1_max = o.quick ? 16u : 256u;
    s.rounds = o.quick ? std::vector<std::uint32_t>{1} : std::vector<std::uint32_t>{1, 2, 4, 8};
    s.rt_rounds_max = o.quick ? 1u : 2u;
  }
  if (name == "cornell") {
    s.cluster_paths = o.quick ? std::vector<std::uint32_t>{256}
                              : std::vector<std::uint32_t>{2048, 4096, 8192, 16384, 32768};
    // 22 rounds: the last the raster renders within pt 1024 spp's time (about 30 s, the end of
    // the range the comparison at equal time covers).
    s.rounds =
        o.quick ? std::vector<std::uint32_t>{1, 2} : std::vector<std::uint32_t>{1, 2, 4, 8, 16, 22};
    s.rt_rounds_max = o.quick ? 2u : 4u; // rt-vpl: about 4 s a round at 256x256
  }
  if (is_real_scene(name) || name == "sphere2m") {
    // Full, zdm2 and godot: pt up to 1024 spp and the default up to 8 rounds (about 30 s on
    // godot, 50 s on zdm2), against a 4096-spp reference (a 1024-spp one carries a third of pt
    // 1024 spp's error per 4x4 block: godot 1.9e-4 of 5.5e-4).
    s = o.quick ? Sweep{64, 256, {16}, {16}, {4, 16}, 0}
                : Sweep{128, 1024, {16, 64, 256}, {16, 64, 256}, {4, 16, 64, 256}, 0};
    s.every_sequence = false;
    s.k1_max = 16;
    if (!o.quick) s.cluster_paths = {64, 256, 1024};
    if (!o.quick && is_real_scene(name)) {
      s.reference_spp = 4096;
      s.spp.push_back(1024);
      s.rounds = {1, 2, 4, 8};
    }
  }
  if (o.size > 0) s.size = o.size;
  if (o.reference_spp > 0) s.reference_spp = o.reference_spp;
  return s;
}

struct BenchScene {
  std::string name;
  Scene scene;
  double load_seconds;
};

BenchScene make_scene(const std::string& name, const BenchOptions& o, const Sweep& sw, Log& log) {
  const auto t0 = Clock::now();
  Scene s;
  if (is_real_scene(name)) {
    s = load_real_scene(name, o.shared, log);
  } else if (name == "cornell") {
    s = load_gltf(o.cornell, log);
  } else if (name == "cornell_glossy") { // beside the Cornell box: data/cornell_glossy.gltf
    s = load_gltf((std::filesystem::path(o.cornell).parent_path() / "cornell_glossy.gltf").string(),
                  log);
  } else if (name == "sphere") {
    s = integrating_sphere(1.0, 0.7, o.quick ? 2 : 3).scene;
  } else if (name == "large") {
    s = load_gltf(o.cornell, log); // the Cornell box, every triangle split 4^levels times
    subdivide(s, sw.large_levels);
    s.source = "cornell_subdivided";
  } else if (name == "sphere2m") {
    // The Cornell box with a UV sphere of 2.1M triangles (8k quick) in front of the tall block:
    // the scale study's curved series at its largest (apps/bench/bench_scale.cpp).
    s = load_gltf(o.cornell, log);
    add_sphere(s, {0.3f, 0.33f, 0.3f}, 0.09f, sphere_rings_for(o.quick ? 8192 : 2097152),
               add_material(s, glm::vec3(0.7f)));
    finish(s);
    s.source = "cornell_sphere";
  } else {
    throw Error("", "--scene",
                "unknown bench scene '" + name +
                    "' (cornell, cornell_glossy, sphere, large, sphere2m, zdm2, godot, "
                    "godot_glossy)");
  }
  return {name, std::move(s), since(t0)};
}

// The converged reference, cached as OUT/ref_<scene>_<W>x<H>_spp<S>_seed0.exr.
Image reference(const BenchScene& b, const RayScene& rays, const View& view, std::uint32_t spp,
                const std::string& out_dir, Log& log) {
  const std::string path =
      fmt::format("{}/ref_{}_{}x{}_spp{}_seed0.exr", out_dir, b.name, view.width, view.height, spp);
  if (std::filesystem::exists(path)) return read_exr(path);
  log.info(fmt::format("bench: path-tracing the {} reference ({} spp)", b.name, spp));
  const auto t0 = Clock::now();
  const Image image = path_trace(b.scene, rays, view, {spp, 0, 0, 1000});
  log.info(fmt::format("bench: the {} reference took {:.1f} s", b.name, since(t0)));
  write_exr(path, image);
  return image;
}

void score(BenchRow& row, const Image& image, const Image& ref) {
  row.peak_mib = peak_memory_mib();
  const ImageMetrics m = compare_images(image, ref);
  row.rmse = m.rmse;
  row.relmse = m.relmse;
  row.relmse_block4 = compare_images(image, ref, 4).relmse;
  row.mean_ratio = (m.mean_ratio[0] + m.mean_ratio[1] + m.mean_ratio[2]) / 3.0;
  row.width = image.width();
  row.height = image.height();
}

// A new row; the peak memory counts from here.
BenchRow base_row(const BenchScene& b, double bvh, const char* estimator) {
  reset_peak_memory();
  BenchRow row;
  row.scene = b.name;
  row.triangles = b.scene.triangle_count();
  row.estimator = estimator;
  row.load = b.load_seconds;
  row.bvh = bvh;
  return row;
}

// One line per row; rows with VPLs add the cost per VPL (1 / vpls_per_second) and, for the
// raster, its split into the shadow and shading passes' GPU time per VPL.
void log_row(const BenchRow& r, Log& log) {
  std::string line =
      fmt::format("bench: {:8} {:9} {:16} N {:5} spp {:5} {:7.2f} s  relMSE {:.3e}", r.scene,
                  r.estimator, r.sequence, r.paths, r.spp, r.total, r.relmse);
  if (r.vpls > 0 && r.vpls_per_second > 0)
    line += fmt::format("  {} VPLs {:.3f} ms/VPL", r.vpls, 1e3 / r.vpls_per_second);
  const double vpls = static_cast<double>(r.vpls);
  if (r.vpls > 0 && r.shadow >= 0 && r.shading >= 0)
    line += fmt::format(" (shadow {:.3f}, shading {:.3f})", 1e3 * r.shadow / vpls,
                        1e3 * r.shading / vpls);
  if (r.rounds > 0) line += fmt::format("  rounds {}", r.rounds);
  if (r.peak_mib > 0) line += fmt::format("  peak {:.0f} MiB", r.peak_mib);
  if (r.setup > 0) line += fmt::format("  set-up {:.2f} s", r.setup);
  log.info(line);
}

// The raster's N for one interleave factor (k = 1: the reference mode).
std::vector<std::uint32_t> raster_paths(const Sweep& sw, int interleave) {
  const std::uint32_t max = interleave == 1 ? std::min(sw.raster_max, sw.k1_max) : sw.raster_max;
  std::vector<std::uint32_t> paths;
  for (std::uint32_t n : sw.paths)
    if (n <= max) paths.push_back(n);
  return paths;
}

// What every estimator of one scene's sweep is scored against.
struct Target {
  const BenchScene& b;
  const RayScene& rays;
  View view;
  Image ref;
  double bvh; // seconds to build `rays`
};

// The raster's options as `irad render` sets them by default for the bench's image (the
// occluder planes chosen for the scene: irad::choose_shadow_planes), with the GPU timers.
RasterOptions bench_raster_options(const Target& g) {
  RasterOptions o;
  o.gpu_timers = true;
  const int resolution = shadow_resolution_for(0, g.view.width, g.view.height);
  o.shadow_lod.planes =
      choose_shadow_planes(g.b.scene, g.rays, ShadowPlanes::Auto, resolution).planes;
  return o;
}

// The VPL estimators as `irad render` runs them: the walk's VPLs with the local clamp
// (core/lights/clamp_field.h), or the global one (`local` false).
VplSet bench_walk(const Target& g, std::uint32_t n, SequenceKind seq, bool local, Log& log) {
  VplSet vpls = quasi_random_walk(g.b.scene, g.rays, {n, 64, seq, 1}, log);
  if (local) apply_local_clamp(vpls, g.b.scene.bounds.diagonal(), {8, 0.5f, 0.05f, 1e-4f});
  return vpls;
}

// Adds the screen-space compensation of the clamp (walk/compensation/screen_compensation.h) to
// `image`.
void bench_compensate(const Target& g, const VplSet& vpls, Image& image, BenchRow& row) {
  if (g.b.scene.has_specular()) return;
  const auto t0 = Clock::now();
  const Image residual = screen_space_residual(g.b.scene, g.rays, g.view, vpls, image, {});
  for (std::size_t i = 0; i < image.pixels().size(); ++i)
    image.pixels()[i] += glm::vec4(glm::vec3(residual.pixels()[i]), 0.0f);
  row.compensation = since(t0);
}

// The default raster (interleaved, k = 4, the local clamp and its screen-space compensation) over
// every sequence (or Halton only), the reference mode (every VPL shades every pixel) and the
// global clamp without compensation with Halton, so all meet the other estimators on one plot.
// The large and real scenes' raster passes are slow on a CPU: they take fewer N.
void bench_raster(const Target& g, const Sweep& sw, std::vector<BenchRow>& rows, Log& log) {
  struct Variant {
    int interleave;
    bool local; // the local clamp and its compensation
  };
  for (const auto [interleave, local] : {Variant{4, true}, Variant{1, true}, Variant{4, false}}) {
    // The global clamp's variant only over the reference mode's N (it is there for comparison).
    const std::vector<std::uint32_t> paths = raster_paths(sw, local ? interleave : 1);
    if (paths.empty()) continue;
    RasterOptions raster_options = bench_raster_options(g);
    raster_options.interleave = interleave;
    RasterRenderer raster(g.b.scene, raster_options);
    const auto t_setup = Clock::now();
    raster.render(g.view, quasi_random_walk(g.b.scene, g.rays, {1, 64}, log));
    const double setup = since(t_setup);
    const char* estimator = !local ? "raster-global" : interleave == 1 ? "raster-k1" : "raster";
    for (SequenceKind seq :
         {SequenceKind::Halton, SequenceKind::ScrambledHalton, SequenceKind::Random}) {
      if ((interleave == 1 || !local || !sw.every_sequence) && seq != SequenceKind::Halton)
        continue;
      for (std::uint32_t n : paths) {
        BenchRow row = base_row(g.b, g.bvh, estimator);
        row.sequence = sequence_name(seq);
        row.paths = n;
        row.setup = setup;
        const auto t0 = Clock::now();
        const VplSet vpls = bench_walk(g, n, seq, local, log);
        row.walk = since(t0);
        RasterTimings t;
        Image image = raster.render(g.view, vpls, &t);
        if (local) bench_compensate(g, vpls, image, row);
        row.total = since(t0);
        row.vpls = t.passes;
        row.shadow = t.shadow_gpu;
        row.shading = t.shading_gpu;
        row.readback = t.readback;
        row.vpls_per_second = static_cast<double>(t.passes) / (t.passes_seconds + t.readback);
        score(row, image, g.ref);
        log_row(row, log);
        rows.push_back(row);
      }
    }
  }
}

// The default raster over the representatives of the walk's VPLs (walk/vpls/vpl_clustering.h), with
// a cluster per 16 VPLs (64 to 2048 clusters).
void bench_clusters(const Target& g, const Sweep& sw, std::vector<BenchRow>& rows, Log& log) {
  if (sw.cluster_paths.empty()) return;
  RasterRenderer raster(g.b.scene, bench_raster_options(g));
  const auto t_setup = Clock::now();
  raster.render(g.view, quasi_random_walk(g.b.scene, g.rays, {1, 64}, log));
  const double setup = since(t_setup);
  for (std::uint32_t n : sw.cluster_paths) {
    BenchRow row = base_row(g.b, g.bvh, "raster-clusters");
    row.sequence = "halton";
    row.paths = n;
    row.setup = setup;
    const auto t0 = Clock::now();
    const VplSet walk = bench_walk(g, n, SequenceKind::Halton, true, log);
    VplClusteringOptions o;
    o.clusters = std::clamp<std::size_t>(walk.vpls.size() / 16, 64, 2048);
    const VplSet vpls = cluster_vpls(g.b.scene, g.rays, g.view, walk, o).set;
    row.walk = since(t0);
    RasterTimings t;
    Image image = raster.render(g.view, vpls, &t);
    bench_compensate(g, vpls, image, row);
    row.total = since(t0);
    row.vpls = walk.vpls.size();
    row.shadow = t.shadow_gpu;
    row.shading = t.shading_gpu;
    row.readback = t.readback;
    row.vpls_per_second = static_cast<double>(walk.vpls.size()) / row.total;
    score(row, image, g.ref);
    log_row(row, log);
    rows.push_back(row);
  }
}

// `irad render`'s default (the light budget: --paths auto --clusters auto --interleave auto,
// core/lights/light_budget.h) through the library, with the raster and with rt-vpl, one row for
// each of the sweep's rounds; `total` leaves out render()'s load (the BVH, in `bvh`), and includes
// the GL context and shaders, as the CLI pays them.
void bench_default(const Target& g, const Sweep& sw, std::vector<BenchRow>& rows, Log& log) {
  for (const Estimator estimator : {Estimator::Raster, Estimator::RtVpl})
    for (const std::uint32_t rounds : sw.rounds) {
      if (estimator == Estimator::RtVpl && rounds > sw.rt_rounds_max) continue;
      RenderOptions o = with_light_budget();
      o.size = std::pair{g.view.width, g.view.height};
      o.estimator = estimator;
      o.rounds = rounds;
      const RenderResult r = render(g.b.scene, o, log);
      BenchRow row = base_row(g.b, g.bvh,
                              estimator == Estimator::Raster ? "raster-default" : "rt-vpl-default");
      row.sequence = "halton";
      row.rounds = r.rounds;
      row.paths = r.vpls.paths;
      row.vpls = r.walk_vpls;
      row.walk = r.seconds.walk + r.seconds.cluster;
      row.readback = r.seconds.readback;
      row.trace = r.seconds.trace;
      row.compensation = r.seconds.compensation;
      row.total = r.seconds.total - r.seconds.load;
      row.vpls_per_second = static_cast<double>(r.walk_vpls) * r.rounds / row.total;
      score(row, r.image, g.ref);
      log_row(row, log);
      rows.push_back(row);
    }
}

// The same Halton VPLs with ray-traced visibility.
void bench_rt_vpl(const Target& g, const Sweep& sw, std::vector<BenchRow>& rows, Log& log) {
  for (std::uint32_t n : sw.rt_paths) {
    BenchRow row = base_row(g.b, g.bvh, "rt-vpl");
    row.sequence = "halton";
    row.paths = n;
    const auto t0 = Clock::now();
    const VplSet vpls = bench_walk(g, n, SequenceKind::Halton, true, log);
    row.walk = since(t0);
    const auto t1 = Clock::now();
    Image image = trace_vpls(g.b.scene, g.rays, g.view, vpls, {0.05f, 0});
    row.trace = since(t1);
    bench_compensate(g, vpls, image, row);
    row.total = since(t0);
    row.vpls = vpls.vpls.size();
    row.vpls_per_second = static_cast<double>(row.vpls) / row.trace;
    score(row, image, g.ref);
    log_row(row, log);
    rows.push_back(row);
  }
}

// The path tracer with another seed than the reference's.
void bench_pt(const Target& g, const Sweep& sw, std::vector<BenchRow>& rows, Log& log) {
  for (std::uint32_t spp : sw.spp) {
    BenchRow row = base_row(g.b, g.bvh, "pt");
    row.spp = spp;
    const auto t0 = Clock::now();
    const Image image = path_trace(g.b.scene, g.rays, g.view, {spp, 1, 0, 1000});
    row.trace = row.total = since(t0);
    score(row, image, g.ref);
    log_row(row, log);
    rows.push_back(row);
  }
}

void bench_scene(const BenchScene& b, const Sweep& sw, const BenchOptions& o,
                 std::vector<BenchRow>& rows, Log& log) {
  const auto t0 = Clock::now();
  const RayScene rays(b.scene);
  const double bvh = since(t0);
  log.info(fmt::format("bench: {}: {} triangles, load {:.3f} s, BVH {:.3f} s", b.name,
                       b.scene.triangle_count(), b.load_seconds, bvh));
  const View view = make_view(b.scene.cameras.at(0), b.scene.bounds, sw.size, sw.size);
  const Target g{b, rays, view, reference(b, rays, view, sw.reference_spp, o.out_dir, log), bvh};
  bench_raster(g, sw, rows, log);
  bench_clusters(g, sw, rows, log);
  if (b.name == "cornell" || b.name == "cornell_glossy" || is_real_scene(b.name))
    bench_default(g, sw, rows, log);
  bench_rt_vpl(g, sw, rows, log);
  bench_pt(g, sw, rows, log);
}

} // namespace

std::vector<BenchRow> run_bench(const BenchOptions& o, Log& log) {
  std::filesystem::create_directories(o.out_dir);
  const std::vector<std::string> names =
      o.scenes.empty() ? std::vector<std::string>{"cornell", "sphere", "large"} : o.scenes;
  std::vector<BenchRow> rows;
  for (const std::string& name : names) {
    const Sweep sw = sweep_for(o, name);
    const BenchScene b = make_scene(name, o, sw, log);
    if (is_real_scene(name))
      log.info("bench: wrote the lit copy " + write_lit_copy(b.scene, name, o.out_dir));
    bench_scene(b, sw, o, rows, log);
    write_bench_csv(rows, o.out_dir + "/bench.csv"); // after every scene: a long run keeps its rows
  }
  write_versus_pt(rows, o.out_dir + "/versus_pt.csv", log);
  if (o.plots) write_bench_plots(rows, o.out_dir, log);
  // The Cornell box's triangle-count study: not for a run of real scenes only.
  const bool only_real = !names.empty() && std::all_of(names.begin(), names.end(), is_real_scene);
  if (o.scale && !only_real) run_scale_study(o, log);
  return rows;
}

void write_bench_csv(const std::vector<BenchRow>& rows, const std::string& path) {
  std::ofstream out(path);
  out << "scene,triangles,estimator,sequence,paths,spp,vpls,width,height,seconds_load,"
         "seconds_walk,seconds_shadow_gpu,seconds_shading_gpu,seconds_readback,seconds_trace,"
         "seconds_total,vpls_per_second,rmse,relmse,mean_ratio,seconds_bvh,peak_mib,"
         "seconds_setup,relmse_block4,seconds_compensation,rounds\n";
  for (const BenchRow& r : rows)
    out << fmt::format("{},{},{},{},{},{},{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},"
                       "{:.6f},{:.2f},{:.6g},{:.6g},{:.6f},{:.6f},{:.1f},{:.4f},{:.6g},{:.4f},{}\n",
                       r.scene, r.triangles, r.estimator, r.sequence, r.paths, r.spp, r.vpls,
                       r.width, r.height, r.load, r.walk, r.shadow, r.shading, r.readback, r.trace,
                       r.total, r.vpls_per_second, r.rmse, r.relmse, r.mean_ratio, r.bvh,
                       r.peak_mib, r.setup, r.relmse_block4, r.compensation, r.rounds);
  if (!out) throw Error(path, "", "cannot write");
}

} // namespace irad::apps
