// irad bench's cost against the triangle count (apps/bench/bench.h run_scale_study): the same image
// at 8k to 2M triangles, two ways of getting there.
//   flat:   the Cornell box split into 32 x 4^L triangles (L = 4..8): subdivided walls, which the
//           shadow level of detail simplifies to almost nothing (an easy case);
//   sphere: the Cornell box (32 triangles) with a UV sphere of about as many triangles floating
//           in it: a curved surface that keeps its detail where a VPL is near.
// Per row: the BVH and the walk, rt-vpl per VPL, the cluster hierarchy's set-up time and size
// (core/mesh/hierarchy/mesh_clusters.h), and per RasterOptions::shadow_lod (off, cull, on) the
// raster per VPL (wall clock, the median of `runs` renders after a warm-up) split into the shadow
// and the shading passes' GPU time. 128x128, interleave 1, batch 16, N = 16.
//
// run_shadow_lod_error: what the shadow level of detail costs in error on real scenes (zdm2,
// godot): the same VPLs through the raster with shadow-lod off and on and through rt-vpl
// (exact visibility), interleave 1 so that the difference is the shadow maps'.
#include "apps/bench/bench.h"
#include "apps/bench/bench_real_scenes.h"
#include "apps/bench/stopwatch.h"

#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/image/image_metrics.h"
#include "core/mesh/hierarchy/mesh_clusters.h"
#include "core/mesh/sphere_mesh.h"
#include "core/scene/scene_builder.h"
#include "core/util/error.h"
#include "raster/raster_renderer.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/vpls/quasi_random_walk.h"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <fstream>

namespace irad::apps {

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

Scene scale_scene(const BenchOptions& o, const std::string& series, int levels, Log& log) {
  Scene s = load_gltf(o.cornell, log);
  const std::size_t triangles = s.triangle_count() << (2 * levels); // 32 x 4^L
  if (series == "flat") {
    subdivide(s, levels);
  } else {
    add_sphere(s, {0.3f, 0.33f, 0.3f}, 0.09f, sphere_rings_for(triangles),
               add_material(s, glm::vec3(0.7f)));
    finish(s);
  }
  s.source = "cornell_" + series;
  return s;
}

struct RasterCost {
  double per_vpl = 0, shadow = 0, shading = 0; // seconds per VPL (medians)
};

RasterCost raster_cost(const Scene& s, const View& view, const VplSet& vpls, ShadowLodMode mode,
                       int runs) {
  RasterOptions ro;
  ro.interleave = 1;
  ro.gpu_timers = true;
  ro.shadow_lod.mode = mode;
  RasterRenderer raster(s, ro);
  // Warm-up (context, upload, the cluster hierarchy) with the first path's VPLs.
  VplSet first = vpls;
  first.vpls.resize(std::min<std::size_t>(first.vpls.size(), 8));
  raster.render(view, first);
  std::vector<double> total, shadow, shading;
  for (int r = 0; r < runs; ++r) {
    RasterTimings t;
    raster.render(view, vpls, &t);
    const double n = static_cast<double>(std::max<std::size_t>(t.passes, 1));
    total.push_back((t.passes_seconds + t.readback) / n);
    shadow.push_back(t.shadow_gpu / n);
    shading.push_back(t.shading_gpu / n);
  }
  return {median(total), median(shadow), median(shading)};
}

const char* mode_name(ShadowLodMode m) {
  return m == ShadowLodMode::Off ? "off" : m == ShadowLodMode::Cull ? "cull" : "on";
}

} // namespace

void run_scale_study(const BenchOptions& o, Log& log) {
  const std::string path = o.out_dir + "/scale.csv";
  std::ofstream out(path);
  out << "series,triangles,seconds_bvh,walk_paths,seconds_walk,vpls,seconds_rtvpl_per_vpl,"
         "seconds_clusters,cluster_mib,shadow_lod,seconds_raster_per_vpl,seconds_shadow_per_vpl,"
         "seconds_shading_per_vpl\n";
  const int runs = o.quick ? 1 : 3;
  for (const std::string series : {"flat", "sphere"})
    for (int levels = 4; levels <= (o.quick ? 5 : 8); ++levels) {
      const Scene s = scale_scene(o, series, levels, log);
      const auto t0 = Clock::now();
      const RayScene rays(s);
      const double bvh = since(t0);
      const auto t1 = Clock::now();
      const VplSet big = quasi_random_walk(s, rays, {1024, 64}, log);
      const double walk = since(t1);
      const VplSet small = quasi_random_walk(s, rays, {16, 64}, log);
      const View view = make_view(s.cameras.at(0), s.bounds, 128, 128);
      const auto t2 = Clock::now();
      trace_vpls(s, rays, view, small, {0.05f, 0});
      const double rt_per_vpl = since(t2) / static_cast<double>(small.vpls.size());
      const auto t3 = Clock::now();
      const MeshClusters clusters = build_mesh_clusters(s);
      const double setup = since(t3);
      const double mib = static_cast<double>(clusters.bytes()) / (1 << 20);
      for (ShadowLodMode mode : {ShadowLodMode::Off, ShadowLodMode::Cull, ShadowLodMode::On}) {
        const RasterCost c = raster_cost(s, view, small, mode, runs);
        out << fmt::format("{},{},{:.4f},1024,{:.4f},{},{:.6f},{:.4f},{:.2f},{},{:.6f},{:.6f},"
                           "{:.6f}\n",
                           series, s.triangle_count(), bvh, walk, small.vpls.size(), rt_per_vpl,
                           setup, mib, mode_name(mode), c.per_vpl, c.shadow, c.shading);
        out.flush();
        log.info(fmt::format("bench: scale {} {} triangles, shadow-lod {}: raster {:.2f} ms/VPL "
                             "(shadow {:.2f}, shading {:.2f}), rt-vpl {:.2f} ms/VPL; clusters "
                             "{:.2f} s, {:.1f} MiB",
                             series, s.triangle_count(), mode_name(mode), 1e3 * c.per_vpl,
                             1e3 * c.shadow, 1e3 * c.shading, 1e3 * rt_per_vpl, setup, mib));
      }
      (void)big;
    }
  if (!out) throw Error(path, "", "cannot write");
}

void run_shadow_lod_error(const BenchOptions& o, Log& log) {
  const std::string path = o.out_dir + "/shadow_lod_error.csv";
  std::ofstream out(path);
  out << "scene,triangles,paths,vpls,width,height,shadow_lod,texels,occlusion,"
         "seconds_raster_per_vpl,seconds_shadow_per_vpl,shadow_triangles_per_vpl,relmse_vs_rtvpl,"
         "relmse4_vs_rtvpl,mean_ratio_vs_rtvpl,"
         "relmse_vs_off,mean_ratio_vs_off\n";
  const int size = o.size > 0 ? o.size : 128;
  const std::uint32_t paths = o.quick ? 4 : 16;
  for (const std::string& name : o.scenes) {
    if (!is_real_scene(name)) continue;
    const Scene s = load_real_scene(name, o.shared, log);
    const RayScene rays(s);
    const VplSet vpls = quasi_random_walk(s, rays, {paths, 64}, log);
    const View view = make_view(s.cameras.at(0), s.bounds, size, size);
    const Image traced = trace_vpls(s, rays, view, vpls, {0.05f, 0});
    Image off;
    // Occlusion culling (the default) on and off where it applies; it leaves the image as it is.
    const ShadowLodOptions settings[] = {
        {ShadowLodMode::Off, 0.0f, false}, {ShadowLodMode::Cull, 0.0f, false},
        {ShadowLodMode::Cull, 0.0f, true}, {ShadowLodMode::On, 0.5f, false},
        {ShadowLodMode::On, 0.25f, true},  {ShadowLodMode::On, 0.5f, true},
        {ShadowLodMode::On, 1.0f, true},   {ShadowLodMode::On, 2.0f, true}};
    for (const ShadowLodOptions& lod : settings) {
      const ShadowLodMode mode = lod.mode;
      RasterOptions ro;
      ro.interleave = 1;
      ro.gpu_timers = true;
      ro.shadow_lod = lod;
      RasterRenderer raster(s, ro);
      RasterTimings t;
      const Image image = raster.render(view, vpls, &t);
      if (mode == ShadowLodMode::Off) off = image;
      const double n = static_cast<double>(std::max<std::size_t>(t.passes, 1));
      const ImageMetrics rt = compare_images(image, traced), rt4 = compare_images(image, traced, 4);
      const ImageMetrics full = compare_images(image, off);
      const double triangles = static_cast<double>(t.shadow_triangles) / n;
      out << fmt::format("{},{},{},{},{},{},{},{},{},{:.6f},{:.6f},{:.0f},{:.6g},{:.6g},{:.6f},"
                         "{:.6g},{:.6f}\n",
                         name, s.triangle_count(), paths, vpls.vpls.size(), size, size,
                         mode_name(mode), lod.texels, lod.occlusion ? 1 : 0,
                         (t.passes_seconds + t.readback) / n, t.shadow_gpu / n, triangles,
                         rt.relmse, rt4.relmse, rt.mean_ratio[1], full.relmse, full.mean_ratio[1]);
      out.flush();
      log.info(fmt::format("bench: {} shadow-lod {} ({} texels, occlusion {}): {:.2f} ms/VPL "
                           "(shadow {:.2f}, {:.0f} triangles); relMSE against rt-vpl {:.4g} (4x4 "
                           "blocks {:.4g}), against off {:.3g}",
                           name, mode_name(mode), lod.texels, lod.occlusion ? "on" : "off",
                           1e3 * (t.passes_seconds + t.readback) / n, 1e3 * t.shadow_gpu / n,
                           triangles, rt.relmse, rt4.relmse, full.relmse));
    }
  }
  if (!out) throw Error(path, "", "cannot write");
}

} // namespace irad::apps
