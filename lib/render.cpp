#include "irad/render.h"

#include "core/animation/animation.h"
#include "core/lights/clamp_field.h"
#include "core/util/error.h"
#include "core/util/freed_memory.h"
#include "walk/compensation/bias_compensation.h"
#include "walk/estimators/glossy_pass.h"
#include "walk/estimators/mirror_pass.h"
#include "walk/estimators/visibility_tracer.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/rays/ray_scene.h"
#include "walk/vpls/vpl_clustering.h"
#include "walk/walls/thin_walls.h"
#include "walk/walls/wall_cache.h"
#include "walk/walls/wall_scan_ahead.h"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <memory>

namespace irad {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// The one flag the stages poll. Without a cancel_requested callback it is the caller's `cancel`
// itself (a signal handler's flag reaches every stage at once); with one, it is the render's own
// flag, set when the callback or `cancel` says so at a stage boundary or a progress step.
class StopFlag {
public:
  explicit StopFlag(const RenderOptions& o) : token_(o.cancel), callback_(o.cancel_requested) {}
  StopFlag(const StopFlag&) = delete;
  StopFlag& operator=(const StopFlag&) = delete;

  const std::atomic<bool>* flag() const { return callback_ ? &own_ : token_; }
  // Asks the callback (calling thread only); true once cancelled.
  bool poll() {
    if (callback_ && !own_.load() && ((token_ != nullptr && token_->load()) || callback_()))
      own_.store(true);
    const std::atomic<bool>* f = flag();
    return f != nullptr && f->load();
  }

private:
  const std::atomic<bool>* token_;
  std::function<bool()> callback_;
  std::atomic<bool> own_{false};
};

// Everything one render() shares between its stages.
struct Stages {
  const Scene& scene;
  const RenderOptions& options;
  Log& log;
  StopFlag& stop; // render()'s, shared by the rounds
  RenderResult& r;
  std::unique_ptr<RasterRenderer> raster; // made by the first raster stage, kept for the rounds
  double planes_scan = -1.0;              // its wait for the thinnest-wall scan (seconds); -1: none
  // The thinnest-wall scan begun ahead of the raster's first shadow maps (begin_wall_scan):
  // render()'s, which ends it before its rays go.
  std::unique_ptr<WallScanAhead>* wall_scan = nullptr;
  // The raster's shadow hierarchy, building since render() began (early_hierarchy), and the
  // camera's after it (early_camera_hierarchy).
  std::shared_ptr<BackgroundClusters> hierarchy = nullptr, camera_hierarchy = nullptr;
  // The raster's visibility, resolved before anything is built for it (raster_visibility).
  Visibility visibility = Visibility::Maps;

  bool cancelled() {
    r.cancelled = r.cancelled || stop.poll();
    return r.cancelled;
  }
  void progress(std::size_t done, std::size_t total) {
    if (options.progress) options.progress(done, total);
    stop.poll();
  }
};

// A path range that does not start at path 0 holds only its VPLs' light: the visible emitters
// and the background, which every render adds once, belong to the part that starts at 0. The
// estimators add them in their final pass, so the part subtracts the image of no VPLs at all
// (exactly those terms; alpha too, so the parts' alphas add up to 1).
bool without_direct(const RenderOptions& o) {
  return o.walk.first_path > 0;
}
void subtract(Image& image, const Image& direct) {
  for (std::size_t i = 0; i < image.pixels().size(); ++i) image.pixels()[i] -= direct.pixels()[i];
}
VplSet no_vpls(const VplSet& walk) {
  VplSet none = walk;
  none.vpls.clear();
  return none;
}

void run_pt(Stages& s, const RayScene& rays) {
  const auto t0 = Clock::now();
  PathTracerOptions pt = s.options.pt;
  pt.cancel = s.stop.flag();
  s.r.image = path_trace(s.scene, rays, s.r.view, pt, [&](int done, int rows) {
    s.progress(static_cast<std::size_t>(done), static_cast<std::size_t>(rows));
  });
  s.r.seconds.trace = since(t0);
}

// What the occluder planes' automatic choice found (RenderOptions::raster.shadow_lod.planes Auto),
// the scan's seconds from its start and the render's wait for it.
void log_planes(Log& log, const PlaneChoice& planes, int resolution, double scanned,
                double waited) {
  if (planes.thinnest_wall < 0.0f) return;
  const std::string times = fmt::format("scan {:.3f} s, {:.3f} s waited", scanned, waited);
  if (planes.planes == ShadowPlanes::On)
    log.info(fmt::format("occluder planes on: a wall {:.3g} of the diagonal thick, below {:.3g} at "
                         "{} texels per face ({})",
                         planes.thinnest_wall, planes_reach(resolution), resolution, times));
  else
    log.info(fmt::format("occluder planes off: no wall thinner than {:.3g} of the diagonal at {} "
                         "texels per face ({})",
                         planes_reach(resolution), resolution, times));
}

// The raster's k: as asked, or automatically 2 for cluster representatives in images below 512
// pixels on their larger side, else 4. A representative carries a cluster's light, and at k = 4
// a pixel sees a sixteenth of at most 2048 of them, through a filter whose 4x4 tile is a large
// part of a small image. Measured against pt references (k = 4 -> 2; relMSE per pixel / 4x4
// block; time): godot 128x128 2.1e-2 / 3.1e-3 -> 9.2e-3 / 3.0e-3, 6 % more (the speckle on its
// small spheres); zdm2 128x128 1.6e-2 / 4.1e-3 -> 1.1e-2 / 2.7e-3 in the same time; Cornell
// 48x48 block 1.4e-3 -> 3.6e-4; Cornell 256x256 5.6e-4 / 2.29e-4 -> 4.4e-4 / 1.99e-4 for 15-20 %
// more (about level at equal time); Cornell 512x512 7.7e-4 / 3.07e-4 -> 7.2e-4 / 3.08e-4 for
// 22 % more (k = 4 kept there).
int interleave(const RenderOptions& o, const RenderResult& r) {
  if (o.raster.interleave != 0) return o.raster.interleave;
  return r.clusters > 0 && std::max(r.view.width, r.view.height) < 512 ? 2 : 4;
}

// The raster's edge pixels: as asked, or with auto_edges for cluster representatives by the
// rounds (core/lights/light_budget.h; every VPL of a walk per traced pixel would cost what the
// whole image's passes do). Traced at the pixel centre, they would lose the jitter's antialiasing
// where it matters: none with jitter.
EdgePixelMode edge_pixel_mode(const RenderOptions& o, const RenderResult& r) {
  EdgePixelMode mode = o.raster.edge_pixels;
  if (o.auto_edges)
    mode =
        r.clusters > 0 && trace_edge_pixels(o.rounds) ? EdgePixelMode::Listed : EdgePixelMode::Off;
  if (o.raster.jitter && mode == EdgePixelMode::Listed) mode = EdgePixelMode::Off;
  return mode;
}

// The shadow faces' resolution: as asked, else raster_renderer.h's rule, for cluster
// representatives core/lights/light_budget.h's, which asks whether the raster made with `raster`
// (its interleaving and edge pixels resolved) lists the unsure pixels for tracing.
int shadow_resolution(const RenderOptions& o, const RenderResult& r, const RasterOptions& raster) {
  if (o.raster.shadow_resolution != 0) return o.raster.shadow_resolution; // checked by the raster
  const int rule = shadow_resolution_for(0, r.view.width, r.view.height);
  if (r.clusters == 0) return rule;
  return representative_shadow_resolution(rule, r.view.width, r.view.height, o.rounds,
                                          lists_unsure_pixels(raster));
}

// Whether the occluder planes Auto of `scene` are chosen by the thin-wall scan: moving geometry
// takes them without one.
bool planes_scanned(const Scene& scene) {
  return !(scene.animation && scene.animation->moves_geometry());
}

// The planes the scan's answer asks for at `resolution` (raster_renderer.h planes_needed).
PlaneChoice scanned_planes(float thinnest_wall, const CacheResult& cache, int resolution) {
  return {planes_needed(thinnest_wall, resolution) ? ShadowPlanes::On : ShadowPlanes::Off,
          thinnest_wall, cache};
}

// The thinnest-wall scan of the raster's occluder planes Auto begun on its own thread
// (walk/walls/wall_scan_ahead.h) when the raster is made: from then to its first shadow maps the GL
// upload and the G-buffer leave a core idle. Where a scan will be asked for (planes_scanned).
void begin_wall_scan(Stages& s, const RayScene& rays, int resolution,
                     const std::filesystem::path& cache) {
  if (s.wall_scan == nullptr || !planes_scanned(s.scene)) return;
  *s.wall_scan = std::make_unique<WallScanAhead>(s.scene, rays, planes_reach(resolution), cache);
}

// The occluder planes Auto of the raster's shadow maps (RasterOptions::choose_planes, asked when
// maps are first drawn to shade): chosen by the thin-wall scan through its cache in `cache` (the
// one begun ahead where there is one), the wait timed, logged and reported in the result.
ShadowPlanes settle_planes(Stages& s, const RayScene& rays, int resolution,
                           const std::filesystem::path& cache) {
  const auto t0 = Clock::now();
  WallScanAhead* ahead = s.wall_scan ? s.wall_scan->get() : nullptr;
  PlaneChoice planes;
  if (ahead != nullptr) {
    CacheResult result;
    const float thinnest = ahead->get(&result);
    planes = scanned_planes(thinnest, result, resolution);
  } else {
    planes = choose_shadow_planes(s.scene, rays, ShadowPlanes::Auto, resolution, cache);
  }
  s.planes_scan = since(t0);
  log_planes(s.log, planes, resolution, ahead ? ahead->seconds() : s.planes_scan, s.planes_scan);
  s.r.shadow_planes = planes.planes == ShadowPlanes::On;
  s.r.thinnest_wall = planes.thinnest_wall;
  s.r.wall_cache = outcome_name(planes.cache.outcome);
  s.r.wall_cache_reason = planes.cache.reason;
  return planes.planes;
}

// The raster renderer, made by the first raster stage: its shadow resolution, interleaving and
// occluder planes (or their choice, settle_planes) for this view and these options, in the
// result. Later rounds reuse it.
RasterRenderer& renderer(Stages& s, const RayScene& rays) {
  if (s.raster) return *s.raster;
  RasterOptions options = s.options.raster;
  options.interleave = interleave(s.options, s.r);
  options.edge_pixels = edge_pixel_mode(s.options, s.r);
  options.shadow_resolution = shadow_resolution(s.options, s.r, options);
  options.visibility = s.visibility;
  if (s.visibility != Visibility::Maps) {
    const float dmin = options.clamp * s.scene.bounds.diagonal();
    const unsigned threads = s.options.pt.threads;
    options.visibility_tracer = [&rays, dmin, threads](const VisibilityRequest& request) {
      trace_visibility(rays, dmin, request, threads);
    };
  }
  // The planes are settled when shadow maps are first drawn to shade: an image whose visibility
  // is traced needs none, nor does Rays, which draws no map.
  if (s.visibility == Visibility::Rays) {
    options.shadow_lod.planes = ShadowPlanes::Off;
  } else if (options.shadow_lod.planes == ShadowPlanes::Auto) {
    begin_wall_scan(s, rays, options.shadow_resolution, options.hierarchy_cache);
    options.choose_planes = [&s, &rays, resolution = options.shadow_resolution,
                             cache = options.hierarchy_cache] {
      return settle_planes(s, rays, resolution, cache);
    };
  }
  s.r.shadow_planes = options.shadow_lod.planes == ShadowPlanes::On; // Auto: settle_planes's
  options.traced_roughness = s.options.traced_roughness;
  options.cancel = s.stop.flag();
  options.gl_messages = [&log = s.log](const std::string& message) { log.warn(message); };
  options.hierarchy_build = s.hierarchy;
  options.camera_build = s.camera_hierarchy;
  s.raster = std::make_unique<RasterRenderer>(s.scene, options); // checks the options
  s.r.shadow_resolution = options.shadow_resolution;
  s.r.interleave = options.interleave;
  s.r.edge_mode = options.interleave > 1 ? edge_mode_name(options.edge_pixels) : "off";
  s.r.gl = s.raster->description();
  return *s.raster;
}

// The raster's edge pixels (EdgePixelMode::Listed) traced over the same VPLs: rt-vpl's values
// where the interleaved filter and the shadow maps are least sure (creases, contacts,
// silhouettes; walk/estimators/vpl_tracer.h trace_vpl_pixels). Timed as the raster's.
void trace_edges(Stages& s, const RayScene& rays, const RasterRenderer& raster) {
  if (!raster.lists_edge_pixels() || s.cancelled()) return;
  const VplTracerOptions options{s.options.raster.clamp, s.options.pt.threads, s.stop.flag(),
                                 s.options.traced_roughness};
  trace_vpl_pixels(s.scene, rays, s.r.view, s.r.vpls, options, raster.edge_pixels(), s.r.image);
}

void run_raster(Stages& s, const RayScene& rays) {
  const auto t0 = Clock::now();
  RasterRenderer& raster = renderer(s, rays);
  RasterTimings timings;
  s.r.image = raster.render(s.r.view, s.r.vpls, &timings,
                            [&s](std::size_t done, std::size_t total) { s.progress(done, total); });
  trace_edges(s, rays, raster); // part of the raster's time
  if (without_direct(s.options) && !s.cancelled())
    subtract(s.r.image, raster.render(s.r.view, no_vpls(s.r.vpls)));
  s.r.seconds.raster = since(t0);
  s.r.seconds.readback = timings.readback;
  s.r.seconds.raster_setup.clear();
  s.r.seconds.hierarchy_beside = raster.hierarchy_beside_times().stages();
  s.r.hierarchy_cache = outcome_name(raster.hierarchy_cache().outcome);
  s.r.hierarchy_cache_reason = raster.hierarchy_cache().reason;
  const StageTimes camera_beside = raster.camera_hierarchy_beside_times();
  for (const auto& stage : camera_beside.stages()) s.r.seconds.hierarchy_beside.push_back(stage);
  s.r.camera_hierarchy_cache = outcome_name(raster.camera_hierarchy_cache().outcome);
  s.r.camera_hierarchy_cache_reason = raster.camera_hierarchy_cache().reason;
  s.r.camera_triangles = timings.camera_triangles;
  s.r.gpu_bytes = {timings.gpu_scene_bytes, timings.gpu_shadow_pages_bytes,
                   timings.gpu_camera_pages_bytes};
  const StageTimes setup = raster.setup_times();
  for (const auto& stage : setup.stages()) s.r.seconds.raster_setup.push_back(stage);
  if (s.planes_scan >= 0.0) s.r.seconds.raster_setup.emplace_back("planes scan", s.planes_scan);
  s.r.passes = timings.passes;
  s.r.shadow_triangles = timings.shadow_triangles;
  s.r.shadow_levels = {timings.shadow_levels_built, timings.shadow_levels_read,
                       timings.shadow_levels_seconds};
  s.r.shadow_helpers = timings.shadow_helpers;
  s.r.visibility = timings.ray_visibility ? "rays" : "maps";
  s.r.seconds.visibility = timings.visibility_seconds;
  s.r.single_passes = timings.single_passes;
  s.r.edge_pixels = timings.edge_pixels;
  s.r.unsure_pixels = timings.unsure_pixels;
  if (s.scene.has_specular() && !s.cancelled()) { // visible mirrors: walk/estimators/mirror_pass.h
    const auto t1 = Clock::now();
    add_mirror_pass(s.scene, rays, s.r.view, s.r.vpls,
                    {s.options.raster.clamp, s.options.pt.threads, s.stop.flag()}, s.r.image);
    s.r.seconds.trace += since(t1);
  }
}

void run_rt_vpl(Stages& s, const RayScene& rays) {
  const auto t0 = Clock::now();
  const VplTracerOptions options{s.options.raster.clamp, s.options.pt.threads, s.stop.flag(),
                                 s.options.traced_roughness};
  s.r.image = trace_vpls(s.scene, rays, s.r.view, s.r.vpls, options);
  if (without_direct(s.options) && !s.cancelled())
    subtract(s.r.image, trace_vpls(s.scene, rays, s.r.view, no_vpls(s.r.vpls), options));
  s.r.seconds.trace = since(t0);
}

// Narrow glossy lobes: their specular light by rays from the camera
// (walk/estimators/glossy_pass.h), the VPL estimator having shaded their diffuse lobe.
void trace_glossy(Stages& s, const RayScene& rays) {
  if (!(s.options.traced_roughness > 0.0f) || s.scene.all_lambertian() || s.cancelled()) return;
  const auto t0 = Clock::now();
  GlossyPassOptions o;
  o.roughness = s.options.traced_roughness;
  o.samples = s.options.glossy_samples;
  o.clamp = s.options.raster.clamp;
  o.environment = !without_direct(s.options); // the background belongs to the part from 0
  o.seed = s.options.pt.seed;
  o.threads = s.options.pt.threads;
  o.cancel = s.stop.flag();
  GlossyPassStats stats;
  add_glossy_pass(s.scene, rays, s.r.view, s.r.vpls, o, s.r.image, &stats);
  s.r.glossy_pixels += stats.pixels;
  s.r.glossy_rays += stats.rays;
  s.r.glossy_on_screen += stats.on_screen;
  s.r.glossy_exact += stats.exact;
  s.r.seconds.glossy += since(t0);
}

// Adds the clamp's residual R(x) to the clamped image.
void compensate(Stages& s, const RayScene& rays) {
  const auto t0 = Clock::now();
  BiasCompensationOptions options;
  options.clamp = s.options.raster.clamp;
  options.samples = s.options.bias_samples;
  options.seed = s.options.pt.seed;
  options.threads = s.options.pt.threads;
  const Image residual = clamp_residual(s.scene, rays, s.r.view, s.r.vpls, options);
  for (std::size_t i = 0; i < residual.pixels().size(); ++i)
    s.r.image.pixels()[i] += glm::vec4(glm::vec3(residual.pixels()[i]), 0.0f);
  s.r.seconds.compensation = since(t0);
}

// Adds the clamp's residual at raster speed: from the clamped image itself where the camera sees
// the gather hits (walk/compensation/screen_compensation.h).
void compensate_on_screen(Stages& s, const RayScene& rays) {
  const auto t0 = Clock::now();
  ScreenCompensationOptions options;
  options.clamp = s.options.raster.clamp;
  options.samples = s.options.screen_samples;
  options.iterations = s.options.screen_iterations;
  options.emission = !without_direct(s.options); // the emitters belong to the part from 0
  options.traced_roughness = s.options.traced_roughness;
  options.seed = s.options.pt.seed;
  options.threads = s.options.pt.threads;
  ScreenCompensationStats stats;
  const Image residual =
      screen_space_residual(s.scene, rays, s.r.view, s.r.vpls, s.r.image, options, &stats);
  for (std::size_t i = 0; i < residual.pixels().size(); ++i)
    s.r.image.pixels()[i] += glm::vec4(glm::vec3(residual.pixels()[i]), 0.0f);
  s.r.compensation_fallback =
      stats.in_reach > 0 ? double(stats.fallback) / double(stats.in_reach) : 0.0;
  s.r.seconds.compensation = since(t0);
}

// The local clamp (core/lights/clamp_field.h) over the walk's VPLs: their clamp distances, and the
// field the residual evaluates at its gather hits. A part of the paths takes the field of all N
// paths (walked again: the walk is cheap), so that its VPLs keep the full render's clamp distances.
void assign_local_clamp(Stages& s, const RayScene& rays) {
  const ClampFieldOptions options{s.options.clamp_neighbours, s.options.clamp_scale,
                                  s.options.raster.clamp};
  const float diagonal = s.scene.bounds.diagonal();
  if (s.options.walk.first_path == 0 && s.options.walk.end_path == 0) {
    apply_local_clamp(s.r.vpls, diagonal, options);
    return;
  }
  WalkOptions all = s.options.walk;
  all.first_path = all.end_path = 0;
  auto field = std::make_shared<const ClampField>(quasi_random_walk(s.scene, rays, all, s.log),
                                                  diagonal, options);
  assign_clamp_distances(s.r.vpls, *field);
  s.r.vpls.clamp_field = std::move(field);
}

// Replaces the walk's VPLs by the representatives of their clusters (walk/vpls/vpl_clustering.h).
void cluster(Stages& s, const RayScene& rays, std::size_t clusters) {
  const auto t0 = Clock::now();
  VplClusteringOptions o;
  o.clusters = clusters;
  o.rows = s.options.cluster_rows;
  o.clamp = s.options.raster.clamp;
  o.local_clamp = s.options.local_clamp;
  o.clamp_neighbours = s.options.clamp_neighbours;
  o.clamp_scale = s.options.cluster_clamp_scale;
  o.seed = s.options.pt.seed;
  o.threads = s.options.pt.threads;
  o.cancel = s.stop.flag();
  Representatives reps = cluster_vpls(s.scene, rays, s.r.view, s.r.vpls, o);
  s.r.cluster_dropped = reps.dropped_fraction;
  s.r.vpls = std::move(reps.set);
  s.r.seconds.cluster = since(t0);
}

// The walk's options, with N from a pilot walk under the automatic budget.
WalkOptions walk_options(Stages& s, const RayScene& rays) {
  WalkOptions walk = s.options.walk;
  if (!s.options.auto_paths) return walk;
  WalkOptions pilot = walk;
  pilot.paths = s.options.budget.pilot_paths;
  pilot.first_path = pilot.end_path = 0;
  const std::size_t vpls = quasi_random_walk(s.scene, rays, pilot, s.log).vpls.size();
  walk.paths = budget_paths(vpls, s.options.budget);
  return walk;
}

// The representatives to draw: as asked, or from the walk's VPL count (the automatic budget).
std::size_t cluster_count(const Stages& s) {
  if (!s.options.auto_clusters) return s.options.clusters;
  if (s.options.walk.first_path > 0 || s.options.walk.end_path > 0) return 0; // a part
  return budget_clusters(s.r.vpls.vpls.size(), s.options.budget);
}

// The walk, one of the VPL estimators, and what the options add to it.
void run_vpl_estimator(Stages& s, const RayScene& rays) {
  const auto t0 = Clock::now();
  s.r.vpls = quasi_random_walk(s.scene, rays, walk_options(s, rays), s.log);
  if (s.options.local_clamp) assign_local_clamp(s, rays);
  s.r.seconds.walk = since(t0);
  if (s.cancelled()) return; // interrupted during the walk: nothing was rendered
  s.r.clusters = cluster_count(s);
  s.r.walk_vpls = s.r.vpls.vpls.size();
  if (s.r.clusters > 0) cluster(s, rays, s.r.clusters);
  if (s.cancelled()) return;
  if (s.options.estimator == Estimator::Raster)
    run_raster(s, rays);
  else
    run_rt_vpl(s, rays);
  trace_glossy(s, rays);
  if (s.options.bias_compensation && !s.cancelled())
    compensate(s, rays);
  else if (s.options.screen_compensation && !s.cancelled())
    compensate_on_screen(s, rays);
  // Not with mirrors (the estimate ignores mirrored VPLs): the stats show -1.
  if (s.options.clamped_fraction && !s.scene.has_specular() && !s.cancelled()) {
    const auto t1 = Clock::now();
    s.r.clamped_fraction = clamped_fraction(s.scene, rays, s.r.view, s.r.vpls,
                                            s.options.raster.clamp, 64, 8, s.options.pt.threads);
    s.r.seconds.statistics += since(t1);
  }
}

// What a path range cannot split exactly (docs/cluster.md): the clamp's residual is gathered
// recursively from the emitters and all VPLs at once, and the raster's pass over visible mirrors
// adds emission and VPL light in one gather; a spp range is the path tracer's, a path range the
// VPL estimators'.
void check_range(const Scene& scene, const RenderOptions& o) {
  const bool paths = o.walk.first_path > 0 || o.walk.end_path > 0;
  const bool samples = o.pt.first_sample > 0 || o.pt.end_sample > 0;
  const bool pt = o.estimator == Estimator::Pt;
  if (paths && pt)
    throw Error("", "--path-range", "is for raster and rt-vpl; pt takes --spp-range");
  if (samples && !pt)
    throw Error("", "--spp-range", "is for pt; raster and rt-vpl take --path-range");
  if (paths && o.bias_compensation)
    throw Error("", "--path-range",
                "cannot split --bias-compensation (its residual is not a sum over paths)");
  if (paths && o.rounds > 1)
    throw Error("", "--path-range", "cannot split --rounds (split the paths of one round)");
  if (paths && o.auto_paths)
    throw Error("", "--path-range",
                "needs --paths N: the parts must share one walk (auto chooses N per scene)");
  if (paths && o.clusters > 0 && !o.auto_clusters)
    throw Error("", "--path-range",
                "cannot split --clusters (the clustering is not a sum over paths)");
  if (paths && scene.has_specular())
    throw Error(scene.source, "--path-range",
                "cannot split a scene with mirrors (the mirror pass is not a sum over paths)");
}

} // namespace

PlaneChoice choose_shadow_planes(const Scene& scene, const RayScene& rays, ShadowPlanes requested,
                                 int resolution, const std::filesystem::path& cache) {
  if (requested != ShadowPlanes::Auto) return {requested, -1.0f, {}};
  if (!planes_scanned(scene)) return {ShadowPlanes::On, -1.0f, {}};
  CacheResult result;
  const float thinnest =
      cached_thinnest_wall(scene, rays, planes_reach(resolution), cache, &result);
  return scanned_planes(thinnest, result, resolution);
}

// Round m of `o` (m > 0): an independent light set, the scrambled Halton walk of seed
// walk.seed + m over the first round's N, with its own clustering and compensation seeds.
RenderOptions round_options(const RenderOptions& o, std::uint32_t m, std::uint32_t paths) {
  RenderOptions r = o;
  r.walk.sequence = SequenceKind::ScrambledHalton;
  r.walk.seed = o.walk.seed + m;
  r.walk.paths = paths;
  r.auto_paths = false;
  r.pt.seed = o.pt.seed + m;
  r.clamped_fraction = false; // the first round's estimate stands
  return r;
}

// RenderOptions::rounds > 1: the mean of the rounds' images. Each round is an unbiased estimate
// of the same image with its own light set, so the mean's variance falls as 1/M, as pt's with its
// samples. A cancelled round is left out; the first round's stats stand for all (seconds and
// passes summed).
void run_rounds(Stages& s, const RayScene& rays) {
  run_vpl_estimator(s, rays);
  std::vector<glm::dvec4> sum(s.r.image.pixels().begin(), s.r.image.pixels().end());
  std::uint32_t done = 1;
  for (std::uint32_t m = 1; m < s.options.rounds && !s.cancelled(); ++m) {
    const RenderOptions o = round_options(s.options, m, s.r.vpls.paths);
    RenderResult rm;
    rm.camera = s.r.camera;
    rm.view = s.r.view;
    Stages sm{s.scene, o, s.log, s.stop, rm, std::move(s.raster)};
    run_vpl_estimator(sm, rays);
    s.raster = std::move(sm.raster);
    if (sm.cancelled()) break; // s.cancelled() says so too: the flag is shared
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += glm::dvec4(rm.image.pixels()[i]);
    ++done;
    StageSeconds& t = s.r.seconds;
    t.walk += rm.seconds.walk;
    t.cluster += rm.seconds.cluster;
    t.raster += rm.seconds.raster;
    t.readback += rm.seconds.readback;
    t.trace += rm.seconds.trace;
    t.compensation += rm.seconds.compensation;
    t.glossy += rm.seconds.glossy;
    s.r.glossy_pixels += rm.glossy_pixels;
    s.r.glossy_rays += rm.glossy_rays;
    s.r.glossy_on_screen += rm.glossy_on_screen;
    s.r.glossy_exact += rm.glossy_exact;
    s.r.passes += rm.passes;
    s.r.shadow_triangles += rm.shadow_triangles;
    s.r.shadow_helpers = std::max(s.r.shadow_helpers, rm.shadow_helpers);
    s.r.gpu_bytes = rm.gpu_bytes;         // one renderer for all rounds: its pages only grow
    s.r.shadow_levels = rm.shadow_levels; // likewise its levels (counted from its start)
    s.r.single_passes += rm.single_passes;
    s.r.edge_pixels = std::max(s.r.edge_pixels, rm.edge_pixels);
    s.r.unsure_pixels = std::max(s.r.unsure_pixels, rm.unsure_pixels);
  }
  s.cancelled(); // a round cancelled: the mean of those done, marked cancelled
  for (std::size_t i = 0; i < sum.size(); ++i)
    s.r.image.pixels()[i] = glm::vec4(sum[i] / double(done));
  s.r.rounds = done;
}

// The raster's visibility (RasterOptions::visibility): Auto stays Auto where the GL will be a
// CPU renderer (expects_cpu_renderer) and the options allow rays (the renderer then asks per
// image whether rays pay, raster/passes/batched_passes.h rays_pay, which draws its probes as
// shadow maps: the hierarchy and the wall scan are still made), else Maps. Rays, decided here
// before the walk, builds nothing for shadow maps.
Visibility raster_visibility(const RenderOptions& o) {
  const RasterOptions& raster = o.raster;
  if (o.estimator != Estimator::Raster || raster.visibility == Visibility::Maps)
    return Visibility::Maps;
  if (raster.visibility == Visibility::Rays) return Visibility::Rays;
  return rays_refused(raster) == nullptr && expects_cpu_renderer(raster.backend, raster.gl_device)
             ? Visibility::Auto
             : Visibility::Maps;
}

// The raster's shadow hierarchy started on its own thread
// (core/mesh/hierarchy/background_clusters.h), where the batched passes will draw from it: raster,
// batches, no jitter, a shadow level of detail, a static scene. On the 2.1M sphere box (256x256,
// cold cache) its one-core stages then overlap the ray-tracing structure, the walk and the GL
// set-up (docs/performance.md "Big scenes"). nullptr elsewhere: the raster builds it where it needs
// it, if it does. A render that ends early (an error, a cancellation) waits for the build to end.
std::shared_ptr<BackgroundClusters> early_hierarchy(const Scene& scene, const RenderOptions& o,
                                                    Visibility visibility) {
  const RasterOptions& raster = o.raster;
  if (o.estimator != Estimator::Raster || visibility == Visibility::Rays || raster.batch <= 1 ||
      raster.jitter || raster.shadow_lod.mode == ShadowLodMode::Off || scene.animation)
    return nullptr;
  return std::make_shared<BackgroundClusters>(scene, shadow_cluster_options(raster.shadow_lod),
                                              raster.hierarchy_cache);
}

// The camera's hierarchy, where the raster will draw its G-buffer through it
// (camera_lod_wanted), started on its own thread once the shadow hierarchy's build (`after`) has
// ended, so that it takes no core from that one. nullptr elsewhere.
std::shared_ptr<BackgroundClusters> early_camera_hierarchy(const Scene& scene,
                                                           const RenderOptions& o,
                                                           const BackgroundClusters* after) {
  if (o.estimator != Estimator::Raster || !camera_lod_wanted(scene, o.raster)) return nullptr;
  return std::make_shared<BackgroundClusters>(scene, camera_cluster_options(),
                                              o.raster.hierarchy_cache, after);
}

// Whether the shadow hierarchy's build (started by early_hierarchy) runs alone before the BVH
// and everything after it: from kBuildFirstFrom triangles, where the build's transient arrays
// (about 50 bytes a triangle) beside the BVH's build and the GL upload set the process's peak.
// Waited for until its cache file is written, so that its indices are in the file, not in memory
// (StoredIndices::leave_in_file), when the BVH is built; a cache hit's read is not waited for.
// Cold renders at 256x256, three rounds in turn against three overlapped: the 10M terrain's
// peak 1091-1097 MiB against 1542-1630, in 18.0-20.9 s against 15.1-17.8 s; the 10M sphere box's
// 1035-1037 MiB against 1354-1356, in 12.2-14.4 s against 10.3-12.3 s (3.6x and 3.9x the decoded
// geometry against 5.0-5.3x).
// Below it the build overlaps the rest, whose cores it shares.
bool builds_first(const Scene& scene) {
  constexpr std::size_t kBuildFirstFrom = std::size_t{1} << 22;
  return scene.triangle_count() >= kBuildFirstFrom;
}

// The BVH's quality: Fast for the raster over a scene of a million triangles or more, where it
// traces far fewer rays than it has triangles (the walk, the clustering's rows, the planes scan,
// the compensation: about 5M rays against 2.1M triangles on the sphere box) and the build is the
// cost that counts; High elsewhere (rt-vpl, pt and the raster's visibility by rays trace rays per
// pixel and VPL).
BvhQuality bvh_quality(const Scene& scene, const RenderOptions& o, Visibility visibility) {
  constexpr std::size_t kFastFrom = std::size_t{1} << 20;
  return o.estimator == Estimator::Raster && visibility != Visibility::Rays &&
                 scene.triangle_count() >= kFastFrom
             ? BvhQuality::Fast
             : BvhQuality::High;
}

RenderResult render(const Scene& scene, const RenderOptions& options, Log& log) {
  RenderResult r;
  StopFlag stop(options);
  Stages s{scene, options, log, stop, r, nullptr};
  const auto t0 = Clock::now();
  r.camera = select_camera(scene, options.camera);
  const auto [width, height] = image_size(r.camera, options.size);
  r.view = make_view(r.camera, scene.bounds, width, height);
  if (scene.has_specular() && options.bias_compensation)
    throw Error(scene.source, "--bias-compensation",
                "the clamp's residual does not handle mirrors (specular materials) yet");

  check_range(scene, options);
  if (options.estimator == Estimator::Raster) { // before the walk; interleave 0: automatic
    RasterOptions raster = options.raster;
    if (raster.interleave == 0) raster.interleave = 4;
    check_raster_options(raster);
  }
  s.visibility = raster_visibility(options);
  s.hierarchy = early_hierarchy(scene, options, s.visibility);
  s.camera_hierarchy = early_camera_hierarchy(scene, options, s.hierarchy.get());
  if (s.hierarchy && builds_first(scene)) {
    s.hierarchy->wait_for_build();
    release_freed_memory(); // the build's transients
  }
  const RayScene rays(scene, bvh_quality(scene, options, s.visibility));
  release_freed_memory(); // the BVH builder's
  // The raster's thinnest-wall scan (begin_wall_scan), declared after `rays`: ends before them.
  std::unique_ptr<WallScanAhead> wall_scan;
  s.wall_scan = &wall_scan;
  r.seconds.load = since(t0);
  if (s.cancelled()) {
    // Interrupted while loading: nothing was rendered.
  } else if (options.estimator == Estimator::Pt) {
    run_pt(s, rays);
  } else if (options.rounds > 1) {
    run_rounds(s, rays);
  } else {
    run_vpl_estimator(s, rays);
  }
  r.seconds.total = since(t0) - r.seconds.statistics;
  if (s.cancelled()) return r;
  if (const std::size_t bad = r.image.non_finite_count(); bad > 0)
    throw Error(scene.source, "image",
                fmt::format("{} pixels are NaN or Inf; nothing written", bad));
  return r;
}

FileRender render_file(const RenderRequest& request, Log& log) {
  const auto t0 = Clock::now();
  FileRender f{load_scene(request.scene_path, request.scene, log), {}};
  const double load = since(t0);
  f.result = render(f.scene, request.render, log);
  f.result.seconds.load += load;
  f.result.seconds.total += load;
  return f;
}

} // namespace irad
