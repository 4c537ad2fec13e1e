#pragma once
// Batched, deferred VPL passes (RasterOptions::batch > 1): the VPLs are drawn B at a time, the
// shadow cubes of a batch into one atlas by one instanced draw (raster/shadow/shadow_atlas.h),
// then the batch's shading screen-space from the camera's G-buffer by one full-screen draw per
// interleaved set (raster/passes/deferred_shader.h). The image is the one the per-VPL passes give
// where every pixel sees one surface (the same cube faces, the same shading maths at the same
// point; tests/test_batched.cpp measures the difference); where faces coincide the per-VPL
// passes light each of them, these passes the one surface the G-buffer kept. What changes is the
// cost: per batch 2 binds, 1 clear, 1 + k^2 draws, and a shading cost of pixels x VPLs that does
// not depend on the triangles, against 6 binds, 5 clears and 6 draws of the whole scene per VPL.
// Every kind of VPL takes these passes: surface, point and spot VPLs' cubes and mirrored VPLs'
// unfolded cubes in the atlas, directional VPLs' orthographic maps in their own atlas.
#include "core/lights/vpl.h"
#include "core/scene/scene.h"
#include "raster/context/pass_timer.h"
#include "raster/image/gbuffer.h"
#include "raster/image/interleaved.h"
#include "raster/passes/deferred_shader.h"
#include "raster/passes/ray_visibility.h"
#include "raster/scene/gpu_scene.h"
#include "raster/shadow/ortho_atlas.h"
#include "raster/shadow/shadow_atlas.h"
#include "raster/shadow/shadow_helpers.h"

#include <functional>
#include <memory>
#include <vector>

namespace irad::gl {

// Where deferred shading reads and adds: the image's G-buffer, and the interleaved atlas's tiles
// (irradiance, the resolve multiplies by the albedo) or, interleaved == nullptr, the image
// `bind_image` binds with its viewport (the target, a ring's path image).
struct DeferredTarget {
  const GBuffer* gbuffer = nullptr;
  const Interleaved* interleaved = nullptr;
  std::function<void()> bind_image;
  // The interleaved atlas's receiver mask (Interleaved::mark_receivers) holds this G-buffer's
  // pixels: the deferred passes draw its Lambertian and glossy pixels apart.
  bool receivers = false;
};

class BatchedPasses {
public:
  // Batches of up to `batch` VPLs (fewer if this GL's texture or uniform-block sizes ask for
  // it) with resolution^2 cube faces and, ortho_resolution > 0 (scenes with directional light),
  // as many orthographic maps of ortho_resolution^2; nullptr when batch < 2 or not even 2 VPLs
  // fit. unsure: the shading's alpha adds the unsure light (DeferredShader). shared: the shadow
  // hierarchy (ShadowAtlas; nullptr: the atlas builds its own). helpers > 0: up to that many
  // threads draw the shadow atlases in contexts shared with `context` (the one current here)
  // while it shades, once a batch draws enough triangles per VPL (kHelperTrianglesPerVpl, 8000).
  static std::unique_ptr<BatchedPasses>
  make(const GladGLContext& api, const Scene& scene, float clamp, int batch, int resolution,
       int ortho_resolution, const ShadowLodOptions& lod, bool unsure,
       LodProvider* shared = nullptr, Context* context = nullptr, int helpers = 0,
       VisibilityTracer rays = nullptr, bool rays_now = false);
  BatchedPasses(const GladGLContext& api, const Scene& scene, float clamp, int requested, int batch,
                int resolution, int ortho_tiles, int ortho_resolution, const ShadowLodOptions& lod,
                bool unsure, LodProvider* shared, Context* context, int helpers,
                VisibilityTracer rays = nullptr, bool rays_now = false);

  // Whether this object serves make(..., batch, resolution, ortho_resolution).
  bool matches(int batch, int resolution, int ortho_resolution) const {
    return batch == requested_ && resolution == atlas_.resolution() &&
           ortho_resolution == (ortho_ ? ortho_->resolution() : 0);
  }
  // Triangles the cube faces drew from the cluster hierarchy since the last draw() began (0
  // without one): what the shadow level of detail leaves of the scene.
  std::size_t shadow_triangles() const { return shadow_triangles_; }
  // Whether directional VPLs can be drawn here (an orthographic atlas was made).
  bool directional() const { return ortho_ != nullptr; }
  // Whether the last draw()'s visibility came from rays (RayVisibility; no shadow map drawn):
  // always with make's rays_now, else, given a tracer (`rays`), where rays_pay said so.
  bool rays() const { return rays_on_; }
  // With rays(): the seconds the tracer took in the last draw().
  double visibility_seconds() const { return rays_on_ ? rays_->seconds() : 0.0; }
  // Given a tracer: the set the next draw()s' VPLs come from (not owned: it must outlive those
  // draws).
  void set_vpls(const VplSet* set) {
    if (rays_) rays_->set_vpls(set);
  }
  // The helper threads drawing the atlases (0 until a batch asked for them).
  int helpers() const { return helpers_ ? helpers_->count() : 0; }

  // Draws the VPLs that carry light (directional ones only when directional()) batch by batch,
  // the mirrored ones last: shadow atlases, then the shading of each set (set_of(vpl)) from
  // `gbuffer` into its tile of `interleaved`, or (nullptr) of all into the target. A batch draws
  // one map per direction it holds (a directional light's VPLs share one). After each batch `after`
  // gets the number of VPLs of `vpls` done; false stops. Returns the number of VPLs drawn.
  std::size_t draw(const std::vector<const Vpl*>& vpls,
                   const std::function<int(const Vpl&)>& set_of, const DeferredTarget& into,
                   const GpuScene& gpu, PassTimer* timer,
                   const std::function<bool(std::size_t)>& after);
  // The lobes the next draw()s' glossy VPLs index (VplSet::lobes; Vpl::lobe); nullptr (the
  // default): every VPL is drawn as Lambertian. Not owned: it must outlive those draws.
  void set_lobes(const std::vector<VplLobe>* lobes) { lobes_ = lobes; }
  // DeferredShader::set_traced_roughness.
  void set_traced_roughness(float r) { shader_.set_traced_roughness(r); }
  // v's lobe under set_lobes, or nullptr.
  const VplLobe* lobe_of(const Vpl& v) const { return lobes_ ? find_lobe(*lobes_, v) : nullptr; }
  // Shades VPLs whose cubes are already in `shadow` (shadow maps kept,
  // raster/shadow/shadow_cache.h): sorted by set on the way, as many per draw as the shader holds.
  void shade(std::vector<AtlasVpl>& vpls, const ShadowLookup& shadow, const DeferredTarget& into);
  // Occluder planes chosen after this object was made (RasterOptions::choose_planes), which was
  // made without them: the first draw() that draws shadow maps to shade calls `settle` once,
  // and `settle` answers through set_planes (rays_pay's probes draw no plane, nor do images
  // whose visibility is traced).
  void ask_planes(std::function<void()> settle) { settle_planes_ = std::move(settle); }
  // Draws the occluder planes from here on (on), or keeps drawing none; asks nothing more.
  void set_planes(bool on);

private:
  struct Entry {
    const Vpl* vpl;
    int set;
  };
  // A batch, and the number of VPLs of draw()'s order up to its end (for draw()'s `after`).
  struct Batch {
    std::vector<Entry> entries;
    std::size_t end = 0;
  };
  // Helper threads are made once a batch drawn here picks at least this many triangles per VPL
  // from the hierarchy (every face's share of the scene without one), and kHelperBatches
  // batches are still to come. From ShadowAtlas's kOcclusionTrianglesPerVpl on, the faces draw
  // in rounds with a readback between them, each a wait of the issuing thread that another
  // thread can fill; below it one context already bins a batch while the last one is
  // rasterized. Measured (llvmpipe, 256x256, raster stage, runs in turn): the 2M terrain (13.3k
  // per VPL) 2.89-3.28 s with two helpers against 3.38-3.93 s without, zdm2 (16.0k) 3.97-4.95
  // against 5.14-5.38 s, godot (5.0k) 2.18-2.31 against 2.07-2.19 s (docs/performance.md).
  static constexpr std::size_t kHelperTrianglesPerVpl = ShadowAtlas::kOcclusionTrianglesPerVpl;
  static constexpr std::size_t kHelperBatches = 8;
  // Given a tracer, rays are taken where rays_pay's probes pick at least a kPixelsPerTriangle-th
  // of the pixels each VPL shades (its interleaved set's) in triangles per VPL: a shadow ray per
  // pixel then costs less than the triangles. Measured (llvmpipe, 2 cores,
  // 256x256, k = 2: 16,384 pixels per VPL; docs/performance.md "Visibility by rays"): a shadow
  // triangle about 0.14 us of one core, a shadow ray about 0.035 us.
  static constexpr std::size_t kPixelsPerTriangle = 4;
  // With rays, a shading upload holds at most this many bytes of answers (a byte per VPL and
  // pixel it shades): 64 VPLs at 1024x1024 with k = 2, 4 at 4096x4096 without interleaving.
  static constexpr std::size_t kRayAnswerBytes = std::size_t{64} << 20;
  // rays_pay's probes: surface VPLs at the points of a grid of pixels this many on a side.
  static constexpr int kProbeGrid = 3;
  // VPLs per batch the helpers draw (at most the requested batch), and the batches drawn here
  // until the helpers are decided. Each helper holds kSlots atlases and a scene of its own in the
  // GL, so that their memory grows with it: on the 10M-triangle terrain (256x256, peak resident
  // set, runs in turn) batches of 64 VPLs with two helpers took 1276-1298 MiB, of 32 1228-1241,
  // of 16 1192-1200, no faster.
  static constexpr int kHelperBatch = 16;
  // Directional maps per batch at most (OrthoAtlas tiles, each ortho_resolution^2).
  static constexpr int kOrthoTiles = 16;
  // draw()'s batches of order[first..] (ShadowAtlas::batch_order) of at most `batch` VPLs and
  // `blocks` atlas blocks each, the first `most` of them.
  std::vector<Batch> form_batches(const std::vector<const Vpl*>& order, std::size_t first,
                                  int batch, int blocks,
                                  const std::function<int(const Vpl&)>& set_of,
                                  const DeferredTarget& into,
                                  std::size_t most = ~std::size_t{0}) const;
  // Makes the helpers when the batch just drawn here (n VPLs) asks for them (draw() asks only
  // while kHelperBatches of their batches follow).
  void consider_helpers(int n, const GpuScene& gpu);
  // Whether rays cost less than maps for the image `into` (make given a tracer, not rays_now):
  // surface VPLs on what a kProbeGrid^2 grid of its pixels sees, facing the camera, are drawn
  // into the atlas, and their triangles per VPL times kPixelsPerTriangle set against the pixels a
  // VPL shades. One answer for every VPL of the image, whatever part of a walk or which round it
  // draws (the VPLs' own triangles would differ between parts).
  bool rays_pay(const GpuScene& gpu, const DeferredTarget& into);
  // The triangles per VPL of the last atlas render of n VPLs (lod: the hierarchy it drew from;
  // without one, every face draws the whole scene).
  std::size_t drawn_per_vpl(const LodProvider* lod, std::size_t n, const GpuScene& gpu) const;
  // The helpers' batch (kHelperBatch, at most this atlas's).
  int helper_batch() const { return std::min(atlas_.batch(), kHelperBatch); }
  // batches[first..] with the helpers drawing the atlases, round robin, each up to two ahead of
  // the shading, which stays in batch order. Returns the number of VPLs drawn.
  std::size_t draw_with_helpers(const std::vector<Batch>& batches, std::size_t first,
                                const DeferredTarget& into, const GpuScene& gpu, PassTimer* timer,
                                const std::function<bool(std::size_t)>& after);
  // shaded_, vpls_ and the indices cubes_ and directional_ for `batch`.
  void gather(const std::vector<Entry>& batch);
  // The gathered batch's directional maps and shading, its cubes in `texture` (and `gradient`)
  // as frames, fars and blocks say.
  void complete(GLuint texture, GLuint gradient, const std::vector<glm::mat3>& frames,
                const std::vector<float>& fars, const std::vector<glm::ivec4>& blocks,
                const DeferredTarget& into, const GpuScene& gpu, PassTimer* timer);
  // The shading's batch at most: more VPLs per full-screen draw than the shadow atlas holds,
  // for the kept shadow maps (GL guarantees 16 KB uniform blocks: 113 VPLs of 144 bytes). 256
  // gives the cached walkthrough no measurable gain over 64 (Cornell box, 256x256, N = 64).
  static constexpr int kShadingBatch = 64;
  // Draws the batch: its atlas, then shade().
  void flush(const std::vector<Entry>& batch, const DeferredTarget& into, const GpuScene& gpu,
             PassTimer* timer);
  // Shades vpls[first..first + n) (sorted by set, n <= the shader's batch).
  void shade_some(const AtlasVpl* vpls, int n, const ShadowLookup& shadow,
                  const DeferredTarget& into);

  // The orthographic maps of the batch's directional VPLs, one per direction; fills the
  // directional entries of shaded_.
  void draw_ortho(const std::vector<std::size_t>& directional, const GpuScene& gpu);

  int requested_;
  ShadowAtlas atlas_;
  std::unique_ptr<OrthoAtlas> ortho_; // scenes with directional light
  DeferredShader shader_;
  // Scratch, reused per batch.
  std::vector<const Vpl*> vpls_;
  std::vector<glm::mat3> frames_;
  std::vector<float> fars_;
  std::vector<glm::ivec4> blocks_;
  std::vector<glm::vec3> directions_;
  std::vector<glm::mat4> lookups_;
  std::vector<glm::ivec2> origins_;
  std::vector<AtlasVpl> shaded_;
  std::vector<std::size_t> cubes_, directional_; // indices into shaded_
  std::size_t shadow_triangles_ = 0;
  Context* context_;
  int max_helpers_;
  bool helpers_asked_ = false; // consider_helpers decided
  std::unique_ptr<ShadowHelpers> helpers_;
  const std::vector<VplLobe>* lobes_ = nullptr;
  std::unique_ptr<RayVisibility> rays_; // given a tracer
  std::function<void()> settle_planes_; // ask_planes's, until called
  bool rays_now_ = false;               // rays for every image (make's rays_now)
  bool rays_on_ = false;                // this image's visibility by rays instead of the atlases
};

} // namespace irad::gl
