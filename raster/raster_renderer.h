#pragma once
// The instant radiosity rasterizer (design.md section 1, "Rasterization"): for every VPL a cube
// shadow map and a shading pass that adds w * C(x) into an RGBA32F framebuffer; the visible
// emitters' L_e once; then readback. Public header: no GL types.
#include "core/camera/view.h"
#include "core/image/image.h"
#include "core/lights/visibility_request.h"
#include "core/lights/vpl.h"
#include "core/mesh/hierarchy/background_clusters.h"
#include "core/mesh/hierarchy/cluster_cache.h"
#include "core/mesh/hierarchy/mesh_clusters.h"
#include "core/scene/scene.h"
#include "core/util/stage_times.h"
#include "raster/context/gl_backend.h"

#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace irad {

// The pixels where the interleaved resolve's window is cut (creases, silhouettes, the border;
// raster/image/edge_pixels.h). Off: the resolve fills them in from their window's side. Shaded:
// the deferred passes (batched) shade them with every set and the resolve keeps their own sum
// (less error per pixel, per 4x4 block it depends on the scene). Listed: only listed
// (RasterRenderer::edge_pixels), for a caller that computes them otherwise (lib/render.cpp
// traces them), and with them the pixels whose shadow lookups were unsure (the batched passes
// then report it: a tenth more shading where the scene has no occluder planes).
enum class EdgePixelMode { Off, Shaded, Listed };

// Where the batched passes' visibility V(y, x) comes from (RasterOptions::visibility).
enum class Visibility { Auto, Maps, Rays };

struct RasterOptions {
  int shadow_resolution = 0; // texels per cube face edge; 0: from the image size (see below)
  float clamp = 0.05f;       // d_min as a fraction of the scene's bounding diagonal
  GlBackend backend = GlBackend::Auto;
  int gl_device = -1;      // EGL device index; -1: the first hardware device
  bool gpu_timers = false; // split the time between shadow maps and shading (benchmarks)
  // 1: every VPL shades every pixel (the reference, the design's shape). k > 1: interleaved
  // sampling, the VPLs split into k x k sets by path, each pixel lit by one set, then a
  // geometry-aware k x k resolve. 4 is the default: at equal time it wins on error against the
  // path tracer (docs/performance.md).
  int interleave = 4;
  // Interleaved: the edge pixels (EdgePixelMode).
  EdgePixelMode edge_pixels = EdgePixelMode::Off;
  // Jittered low-discrepancy sampling (raster/image/pixel_jitter.h): every VPL pass, and the
  // emitters, at a sub-pixel offset, so the accumulation antialiases geometric edges.
  bool jitter = false;
  // VPLs per batch (raster/passes/batched_passes.h): their shadow cubes in one atlas by one
  // instanced draw, their shading by one instanced draw per interleaved set. 1: one shadow cube and
  // one shading pass per VPL (the reference, the same image). 64: the raster stage at 256x256 is
  // 5-10 % shorter than with 16 on the Cornell box, godot, zdm2 and the 2.1M sphere box, as
  // short as with 107 (llvmpipe's most) with 60 % of its atlas memory
  // (docs/performance.md "Batches"); the shadow helpers draw batches of 16. Every kind of VPL and
  // every mode takes them.
  int batch = 64;
  // How the batched shadow atlas draws the opaque triangles (core/mesh/hierarchy/mesh_clusters.h):
  // mode Off every triangle into every face, Cull only the clusters a face sees (the same image),
  // On culled and simplified below `texels` (0.5) shadow texels at the VPL's distance
  // (docs/performance.md). The per-VPL passes (batch 1) always draw everything.
  ShadowLodOptions shadow_lod{};
  // With shadow_lod.planes Auto: the occluder planes' choice, asked once, when shadow maps are
  // first drawn to shade (not for BatchedPasses::rays_pay's probes, which count triangles and
  // draw no plane). An image whose visibility comes from rays never asks, so a scene traced for
  // its shadows is never scanned for thin walls (lib/render.cpp: walk/walls/thin_walls.h). The
  // answer On or Off; unset, Auto draws the planes as On.
  std::function<ShadowPlanes()> choose_planes = nullptr;
  // Threads that draw the batched passes' shadow atlases in GL contexts of their own while this
  // one shades (raster/shadow/shadow_helpers.h), once a batch draws at least 8000 triangles per
  // VPL. -1 (auto): 2 on a CPU renderer (llvmpipe, where the thread that issues the draws does
  // their vertex work) with 2 or more cores, else 0; 0: this context draws them. The image is the
  // same either way.
  int shadow_helpers = -1;
  // Visibility of the batched passes: Maps, the shadow cubes; Rays, the caller's ray tracer
  // (`visibility_tracer`: one shadow ray per VPL and shaded pixel,
  // core/lights/visibility_request.h; no shadow map, hierarchy or helper thread), which needs
  // batches, no jitter, no shaded edge pixels and no camera level of detail; Auto: on a CPU
  // renderer (llvmpipe), when a tracer is given and the options allow it, Rays for an image whose
  // VPLs would draw many shadow triangles against the pixels each shades (BatchedPasses::rays_pay;
  // there rays cost less: docs/performance.md "Visibility by rays"), else Maps.
  Visibility visibility = Visibility::Auto;
  VisibilityTracer visibility_tracer = nullptr;
  // Where the shadow hierarchy is kept between runs (core/mesh/hierarchy/cluster_cache.h): the
  // user's cache folder by default; empty: built every time, never written.
  std::filesystem::path hierarchy_cache = default_cache_folder();
  // The shadow hierarchy's build, where the caller started it before this renderer (irad::render
  // does, beside its ray-tracing structure and walk): taken when it builds what the batched
  // passes need, else ignored and the hierarchy built as without it.
  std::shared_ptr<BackgroundClusters> hierarchy_build = nullptr;
  // The G-buffer and the emitters through the camera's cluster hierarchy
  // (raster/passes/camera_lod.h: the image's frustum culled, each cluster at the coarsest mesh
  // within CameraLod::kPixels): On for static scenes without jitter (camera_lod_wanted), Off:
  // every triangle, every image. Off by default: on llvmpipe at 256x256 the G-buffer is a tenth
  // of a 10M-triangle render and the hierarchy's build doubles its cold cost
  // (docs/performance.md "The camera's hierarchy").
  CameraLodMode camera_lod = CameraLodMode::Off;
  // The camera hierarchy's build, where the caller started it (irad::render does, after the
  // shadow hierarchy's), taken at the first image; without one, built there (through the
  // cache).
  std::shared_ptr<BackgroundClusters> camera_build = nullptr;
  // Glossy scenes: receivers whose roughness lies below this shade only their diffuse lobe from
  // the VPLs a ray can meet (core/lights/vpl.h ray_reachable); the caller adds their specular
  // lobe by rays (walk/estimators/glossy_pass.h, as lib/render.cpp does). 0: none. render() only.
  float traced_roughness = 0.0f;
  // When it becomes true (a signal handler), render() draws no further VPL passes and returns
  // what the passes so far accumulated.
  const std::atomic<bool>* cancel = nullptr;
  // Where the driver's KHR_debug messages go (nullptr: nowhere).
  std::function<void(const std::string&)> gl_messages = nullptr;
};

// Throws irad::Error naming the option (--shadow-res, --clamp, --interleave, --batch) when
// `options` are impossible; the constructor checks them too, a caller may check before its work.
void check_raster_options(const RasterOptions& options);
// Why visibility by rays cannot serve `options` (the option that refuses it), or nullptr.
const char* rays_refused(const RasterOptions& options);
// Whether a renderer of this backend and device will run on a CPU renderer (llvmpipe), as far as
// can be told without making its context (raster/context/gl_context.h).
bool expects_cpu_renderer(GlBackend backend, int device);

// Whether a renderer with `options` lists the unsure pixels beside the edge pixels (the shading
// then reports its unsure light: raster/passes/deferred_shader.h): edge pixels Listed, with
// interleaving.
bool lists_unsure_pixels(const RasterOptions& options);

// The shadow cube resolution used for an image: `requested` if positive, else a quarter of the
// image's larger side rounded up to a power of two, between 64 and 1024.
int shadow_resolution_for(int requested, int width, int height);

// Whether images of `scene` draw through the camera hierarchy (RasterOptions::camera_lod On):
// never for an animated scene or with jitter (its passes draw at other offsets).
bool camera_lod_wanted(const Scene& scene, const RasterOptions& options);
// The options of the camera hierarchy's build (core/mesh/hierarchy/mesh_clusters.h).
ClusterOptions camera_cluster_options();

// Whether faces of `resolution` texels need the occluder planes in a scene whose thinnest wall
// (walk/walls/thin_walls.h) is `thinnest_wall` of the bounding diagonal. The planes change the test
// only for a receiver at distance d from the VPL that lies behind an occluder's plane by less than
// the occluder's depth range across half a texel, d sin(theta) / R (theta: the occluder's angle to
// the ray; 2/R the texel's angle at a face's centre) plus what the bias moves it by (the normal
// offset, at most d 2/R, and the constant 2e-4 of the diagonal). With d at most the diagonal:
// needed when the wall is thinner than 3/R + 2e-4 of the diagonal; 4/R leaves a texel to spare.
bool planes_needed(float thinnest_wall, int resolution);
// The wall thickness (fraction of the diagonal) below which faces of `resolution` need them.
float planes_reach(int resolution);

struct RasterTimings {
  double passes_seconds = 0.0; // wall clock: shadow maps, shading passes and emitters
  double readback = 0.0;       // wall clock: the final readback (waits for the GPU)
  std::size_t passes = 0;      // VPLs drawn
  // Of them, those drawn one at a time (a shadow cube or map and a forward pass each): all with
  // the reference (batch 1), none with the batched passes unless this GL fits no orthographic
  // atlas (directional VPLs).
  std::size_t single_passes = 0;
  // render(): triangles the batched cube faces drew from the shadow hierarchy, all VPLs together
  // (0 when the faces draw the whole scene: shadow-lod off, --batch 1, animated scenes).
  std::size_t shadow_triangles = 0;
  // The triangles the G-buffer drew from the camera hierarchy (0: it drew every triangle).
  std::size_t camera_triangles = 0;
  // render(): the bytes on the GPU of the scene (raster/scene/gpu_scene.h: vertices, indices,
  // textures) and of the pages of the shadow and camera hierarchies drawn so far
  // (raster/shadow/shadow_lod.h), what llvmpipe holds in memory of them.
  std::size_t gpu_scene_bytes = 0, gpu_shadow_pages_bytes = 0, gpu_camera_pages_bytes = 0;
  // render(): the shadow hierarchy's nodes whose deferred levels this renderer built
  // (ShadowLod::build_levels) so far, the seconds that took, and those its cache's late file gave.
  std::size_t shadow_levels_built = 0, shadow_levels_read = 0;
  double shadow_levels_seconds = 0.0;
  // render(): the helper threads that drew shadow atlases (RasterOptions::shadow_helpers; 0 when
  // none were made).
  int shadow_helpers = 0;
  // render(): whether visibility came from rays (RasterOptions::visibility resolved), and the
  // seconds its tracer took.
  bool ray_visibility = false;
  double visibility_seconds = 0.0;
  // Interleaved with edge pixels (RasterOptions::edge_pixels): how many the image has (Shaded:
  // 0 when some VPL took the per-VPL passes, whose light they lack, so the filter kept them).
  std::size_t edge_pixels = 0;
  // Listed: the unsure pixels listed besides them (raster/image/edge_pixels.h).
  std::size_t unsure_pixels = 0;
  // GPU time of the shadow-map and shading passes (GL_TIME_ELAPSED), only with gpu_timers.
  double shadow_gpu = -1.0;
  double shading_gpu = -1.0;
};

using Progress = std::function<void(std::size_t done, std::size_t total)>;

class RasterRenderer {
public:
  // Creates an OSMesa context and uploads the scene. Throws irad::Error on any GL failure.
  RasterRenderer(const Scene& scene, const RasterOptions& options);
  ~RasterRenderer();
  RasterRenderer(const RasterRenderer&) = delete;
  RasterRenderer& operator=(const RasterRenderer&) = delete;

  // pixel(x) = L_e(x) + sum_k C_k(x) over the VPLs, for the given view. Alpha is 1.
  Image render(const View& view, const VplSet& vpls, RasterTimings* timings = nullptr,
               const Progress& progress = {});

  // Shadow maps kept per path (camera motion without ghosting): cache_path draws the shadow cubes
  // of one path's VPLs (at the resolution for a width x height image) into slot `slot`,
  // replacing what the slot held; render_cached shades every cached VPL from `view` without
  // redrawing a shadow map, then adds the emitters. The shadow maps do not depend on the camera,
  // so a moving camera sees no ghosts; they keep the geometry they were drawn with.
  // `lobes`: what the path's glossy VPLs index (Vpl::lobe; QuasiRandomWalk::trace's), kept
  // with them; render_cached evaluates them toward its own camera.
  void cache_path(std::uint32_t slot, const std::vector<Vpl>& vpls, int width, int height,
                  const std::vector<VplLobe>& lobes = {});
  Image render_cached(const View& view, RasterTimings* timings = nullptr);
  std::size_t cache_bytes() const; // GPU memory of the cached shadow maps

  // Re-uploads what the scene's animation moved (after Animation::pose on the scene given to
  // the constructor).
  void scene_changed();

  std::string description() const; // backend and GL renderer
  // The one-time stages so far: "gl context" (its creation), "gl upload" (the scene's buffers,
  // textures and the shaders), and once the batched passes drew from the shadow hierarchy its
  // build and upload (raster/shadow/lod_provider.h).
  StageTimes setup_times() const;
  // The stages of a hierarchy build taken from RasterOptions::hierarchy_build ("hierarchy
  // <stage>"), which ran beside the caller's; setup_times then has "hierarchy wait".
  StageTimes hierarchy_beside_times() const;
  // What the hierarchy cache did (CacheOutcome::Off until the hierarchy was needed).
  CacheResult hierarchy_cache() const;
  // The same two for the camera hierarchy (RasterOptions::camera_lod, camera_build).
  StageTimes camera_hierarchy_beside_times() const;
  CacheResult camera_hierarchy_cache() const;

  // The last image's edge pixels (RasterOptions::edge_pixels; none when Off, without
  // interleaving, or before a render) as Image coordinates (y down), row by row; Listed: with
  // the unsure pixels.
  std::vector<glm::ivec2> edge_pixels() const;
  // Whether the images list their edge pixels for the caller (RasterOptions::edge_pixels Listed).
  bool lists_edge_pixels() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace irad
