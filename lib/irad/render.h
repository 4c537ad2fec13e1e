#pragma once
// One image of a scene with one of the three estimators: walk -> raster (or rt-vpl, or pt),
// with the per-stage times and counts of the render (what `irad render --stats` writes).
//   raster  instant radiosity: the quasi-random walk's VPLs rasterized with shadow maps (OpenGL)
//   rt-vpl  the same VPLs with exact (ray-traced) visibility, on the CPU
//   pt      the path-traced reference, on the CPU
// The image is linear float RGBA; the same scene, options and thread count give the same bits.
// Errors throw irad::Error("FILE", "ELEMENT", "MESSAGE"); warnings go to the Log.
#include "core/camera/view.h"
#include "core/image/image.h"
#include "core/lights/light_budget.h"
#include "core/lights/vpl.h"
#include "core/mesh/hierarchy/cluster_cache.h"
#include "core/scene/scene.h"
#include "core/util/log.h"
#include "irad/scene_setup.h"
#include "raster/raster_renderer.h"
#include "walk/compensation/screen_compensation.h"
#include "walk/estimators/path_tracer.h"
#include "walk/vpls/quasi_random_walk.h"

#include <atomic>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>

namespace irad {

enum class Estimator { Raster, RtVpl, Pt };
// "raster", "rt-vpl" or "pt"; throws irad::Error naming --estimator for any other name.
Estimator parse_estimator(const std::string& name);
const char* estimator_name(Estimator estimator);

// (done, total): raster VPL passes, pt image rows. Called on the thread that called render(),
// never concurrently; it must not throw. pt reports the rows finished whenever the calling
// thread (one of its workers) finishes one, so the last report may come before the last row,
// and a tiny image may give none.
using ProgressCallback = std::function<void(std::size_t done, std::size_t total)>;

struct RenderOptions {
  Estimator estimator = Estimator::Raster;
  std::optional<std::pair<int, int>> size; // WxH; default from the camera's aspect, 512 high
  std::string camera;                      // name or index; empty: the first camera
  WalkOptions walk;
  // clamp and shadow resolution (clamp also for rt-vpl); interleave 0: automatic, 2 when the
  // render draws cluster representatives into an image below 512 pixels, else 4 (lib/render.cpp)
  RasterOptions raster;
  // The clamp distance of the VPL estimators: local (core/lights/clamp_field.h: d(y) = min(cap,
  // clamp_scale * r_k(y)), r_k the distance to the k-th nearest VPL, cap = raster.clamp of the
  // bounding diagonal) or global (raster.clamp of the diagonal everywhere).
  bool local_clamp = true;
  int clamp_neighbours = 8;
  float clamp_scale = 0.5f;
  // Many VPLs through few passes (core/lights/light_clusters.h): the walk's VPLs clustered by
  // `cluster_rows` exactly computed pixels' rows into at most `clusters` representatives, which
  // the estimator draws instead (walk/vpls/vpl_clustering.h: clamped anew at their own density,
  // d = cluster_clamp_scale r_k, larger than the walk's: a representative carries a cluster's
  // light). 0: every VPL drawn.
  std::size_t clusters = 0;
  std::size_t cluster_rows = 256;
  float cluster_clamp_scale = 1.0f;
  // The automatic light budget (core/lights/light_budget.h), `irad render`'s default: auto_paths
  // sets walk.paths from a pilot walk of the scene (refused with a path range: the parts must share
  // one N), auto_clusters sets `clusters` from the walk's VPL count (0 in a path range's part:
  // the clustering is not a sum over paths). Both resolved values are in the RenderResult.
  bool auto_paths = false;
  bool auto_clusters = false;
  // auto_edges: raster.edge_pixels chosen by the rounds (core/lights/light_budget.h
  // trace_edge_pixels: traced, EdgePixelMode::Listed, from 2 rounds on for cluster representatives;
  // never with jitter), in the RenderResult.
  bool auto_edges = false;
  LightBudget budget;
  // Raster and rt-vpl: the mean of `rounds` renders of independent light sets (round m > 0: the
  // scrambled Halton walk of seed walk.seed + m, N of the first round, clustering and compensation
  // seeded pt.seed + m). Its variance falls as 1/rounds; refused with a path range.
  std::uint32_t rounds = 1;
  PathTracerOptions pt; // spp, seed, threads
  bool bias_compensation =
      false; // add the clamp's residual (walk/compensation/bias_compensation.h)
  std::uint32_t bias_samples = 16;
  // The same residual at raster speed (walk/compensation/screen_compensation.h); bias_compensation
  // wins.
  bool screen_compensation = true;
  std::uint32_t screen_samples = 8;
  int screen_iterations = 3;
  // Glossy surfaces whose roughness lies below traced_roughness get their specular lobe from
  // `glossy_samples` rays per pixel (walk/estimators/glossy_pass.h), the VPLs their diffuse lobe
  // (raster and rt-vpl alike); 0: every lobe from the VPLs. Nothing changes for Lambertian scenes.
  // 0.35 and 32: measured on the glossy Cornell box and godot_glossy (docs/performance.md).
  float traced_roughness = 0.35f;
  std::uint32_t glossy_samples = 32;
  bool clamped_fraction = false; // estimate the share of light the clamp removes
  ProgressCallback progress;     // nullptr: no progress reports
  // Cancellation, two ways. `cancel`: a flag any thread or a signal handler may set. When it
  // becomes true, the render stops early: no further stage starts, the running one returns what
  // it has, and the result says cancelled. `cancel_requested`: asked on the calling thread
  // before each stage and at every progress step; true cancels in the same way.
  const std::atomic<bool>* cancel = nullptr;
  std::function<bool()> cancel_requested;
};

// The raster's edge pixels by name into `o`: "auto" (RenderOptions::auto_edges), "traced"
// (EdgePixelMode::Listed), "shaded" or "off", as irad render's --interleave-edges and Python's
// interleave_edges take them; false (and `o` untouched) for any other name.
bool set_edge_pixels(const std::string& name, RenderOptions& o);
// The name RenderResult::edge_mode gives a mode ("traced", "shaded", "off").
const char* edge_mode_name(EdgePixelMode mode);

struct StageSeconds {
  // trace: pt and rt-vpl, or the raster's ray-traced pass over visible mirrors
  // cluster: the rows and the clustering of the VPLs (RenderOptions::clusters)
  // glossy: the narrow lobes' specular rays (walk/estimators/glossy_pass.h)
  double load = 0, walk = 0, cluster = 0, raster = 0, readback = 0, trace = 0, compensation = 0,
         glossy = 0, total = 0;
  // The estimates asked for after the image (RenderOptions::clamped_fraction, which `irad render
  // --stats` asks for): left out of `total`, which is the render's own time.
  double statistics = 0;
  double visibility = 0; // raster, visibility by rays: the tracer's share of `raster`
  // Of `raster`, the one-time stages: RasterRenderer::setup_times in the order they ran (the GL
  // context, the upload, the shadow hierarchy's wait and its upload), then "planes scan": the
  // wait, when shadow maps were first drawn to shade, for the thinnest wall
  // (walk/walls/thin_walls.h), whose scan began with the raster at the lowest priority
  // (walk/walls/wall_scan_ahead.h).
  std::vector<std::pair<std::string, double>> raster_setup;
  // The shadow hierarchy's build stages where it ran on a thread of its own from the start of the
  // render (raster_setup then holds "hierarchy wait", the raster's wait for what was left): not
  // part of `raster`, and overlapping `load`, `walk` and `cluster`.
  std::vector<std::pair<std::string, double>> hierarchy_beside;
};

struct RenderResult {
  Camera camera;
  View view;
  VplSet vpls; // empty for pt; with clusters, the representatives
  // The walk's VPL count; with clusters, the share of their intensity no row saw (dropped).
  std::size_t walk_vpls = 0;
  double cluster_dropped = 0.0;
  std::size_t clusters = 0; // the representatives asked for (0: every VPL drawn)
  std::uint32_t rounds = 1; // rounds averaged (RenderOptions::rounds; fewer when cancelled)
  // When cancelled: what was accumulated (pt, rt-vpl: pixels not done are 0, alpha too).
  Image image;
  // What the shadow hierarchy's cache did (core/mesh/hierarchy/cluster_cache.h outcome_name: off,
  // hit, written, rebuilt, unwritable) and why a file was not used or written.
  std::string hierarchy_cache = "off", hierarchy_cache_reason;
  // The same of the thinnest-wall scan's cache (walk/walls/wall_cache.h), "off" when nothing
  // scanned.
  std::string wall_cache = "off", wall_cache_reason;
  // The shadow hierarchy's for the camera's hierarchy (RasterOptions::camera_lod), and the
  // triangles its cut drew in the last image (0 where it drew every triangle).
  std::string camera_hierarchy_cache = "off", camera_hierarchy_cache_reason;
  std::size_t camera_triangles = 0;
  // The raster's bytes on the GPU (RasterTimings): the scene, the shadow and the camera
  // hierarchies' pages drawn (by the end of the last round).
  struct GpuBytes {
    std::size_t scene = 0, shadow_pages = 0, camera_pages = 0;
  } gpu_bytes;
  StageSeconds seconds;   // load: the camera, view and ray-tracing structure (render_file: also
                          // the loading)
  bool cancelled = false; // stopped early by a cancellation
  std::size_t passes = 0; // VPL passes drawn (raster)
  int shadow_helpers = 0; // threads that drew shadow atlases (raster; RasterOptions)
  std::string visibility; // raster: "rays" or "maps" (RasterOptions::visibility resolved)
  // Triangles the batched shadow faces drew from the shadow hierarchy (raster; RasterTimings)
  std::size_t shadow_triangles = 0;
  // The shadow hierarchy's nodes whose coarser levels were built as its faces first needed them
  // (raster; RasterTimings), the seconds that took (all rounds), and the nodes whose levels the
  // hierarchy cache's late file gave.
  struct ShadowLevels {
    std::size_t built = 0, read = 0;
    double seconds = 0.0;
  } shadow_levels;
  // Of them, those drawn one VPL at a time (--batch 1, the reference; RasterTimings)
  std::size_t single_passes = 0;
  // Interleaved with RasterOptions::edge_pixels: the edge pixels shaded or traced (per image),
  // and how ("off", "shaded", "traced": auto resolved, jitter's veto included)
  std::size_t edge_pixels = 0;
  std::string edge_mode = "off";
  // Traced: the unsure pixels traced besides them (raster/image/edge_pixels.h; per image).
  std::size_t unsure_pixels = 0;
  double clamped_fraction = -1.0; // when requested (not with mirrors)
  // screen compensation: the share of its gather samples in reach evaluated exactly (hidden)
  double compensation_fallback = -1.0;
  // The glossy pass (RenderOptions::traced_roughness; summed over the rounds): pixels whose
  // specular lobe it traced, its rays, and of them those read from the image and those gathered
  // exactly (hidden from the camera).
  std::uint64_t glossy_pixels = 0, glossy_rays = 0, glossy_on_screen = 0, glossy_exact = 0;
  std::string gl;              // GL renderer (raster)
  int shadow_resolution = 0;   // the raster's shadow faces, texels per edge (auto resolved)
  int interleave = 0;          // the raster's k (auto resolved); 0 for rt-vpl
  bool shadow_planes = false;  // the raster's batched passes drew the occluder planes
  float thinnest_wall = -1.0f; // with planes Auto: what walk/walls/thin_walls.h measured (of the
                               // diagonal, up to planes_reach); -1: not measured
};

// The occluder planes (RasterOptions::shadow_lod.planes) for `scene` and faces of `resolution`
// texels: On and Off as requested; Auto becomes On where the scene's thinnest wall
// (walk/walls/thin_walls.h) needs them (raster_renderer.h planes_needed), and always for an
// animation that moves geometry (its walls' gaps change from frame to frame), else Off. The scan
// goes through the cache in `cache` (walk/walls/wall_cache.h; empty: scanned every time).
struct PlaneChoice {
  ShadowPlanes planes = ShadowPlanes::On;
  float thinnest_wall = -1.0f; // as measured for Auto (fraction of the diagonal); else -1
  CacheResult cache;           // what the scan's cache did
};
PlaneChoice choose_shadow_planes(const Scene& scene, const RayScene& rays, ShadowPlanes requested,
                                 int resolution, const std::filesystem::path& cache = {});

// `o` with `irad render`'s (and Python's) automatic choices: the light budget (auto_paths,
// auto_clusters) and the automatic interleaving (raster.interleave 0).
RenderOptions with_light_budget(RenderOptions o = {});

// Renders `scene` (load_scene's, posed and lit) as `options` say. Throws irad::Error on bad
// options and when a finished image holds NaN or Inf pixels.
RenderResult render(const Scene& scene, const RenderOptions& options, Log& log);

// What `irad render` does: load_scene, then render.
struct RenderRequest {
  std::string scene_path;
  SceneOptions scene;
  RenderOptions render;
};
struct FileRender {
  Scene scene;
  RenderResult result;
};
FileRender render_file(const RenderRequest& request, Log& log);

} // namespace irad
