#pragma once
// The shadow cubes of a batch of VPLs in one 2D atlas, drawn by one instanced draw call
// (raster/glsl/batched_shaders.h): the distances |p - y| ShadowCube renders, through the same face
// view-projections (cube_faces), stored as the depth |p - y| / far of a DEPTH_COMPONENT32F
// texture (one buffer to clear and write instead of a colour and a depth buffer), so a lookup
// reads what the VPL's cube map would hold up to float rounding. On llvmpipe a VPL's cube costs
// mostly the fixed cost of its five framebuffer binds, clears and draws and the wait of the next
// shading pass for them; here a batch costs one bind, one clear and one draw.
//
// The atlas is a grid of blocks of (2R + 2h) x 2h texels, h = R/2 + 1 (ShadowCube's front_half).
// A surface VPL needs only its hemisphere: one block holds its +z face, then the front halves
// (h texels deep, with the one texel of margin) of +x and -x side by side, then those of +y and
// -y one over the other. Any other VPL (two-sided, point, spot) takes two blocks of three whole
// faces each. Texels no face covers keep the clear value 1 (far: never shadowed).
//
// With ShadowLodMode Cull or On (core/mesh/hierarchy/mesh_clusters.h) the opaque triangles are
// drawn face by face from a cluster hierarchy (raster/shadow/shadow_lod.h): one glMultiDrawElements
// per face of the clusters it sees (Cull: the same image), at the coarsest level whose error stays
// below ShadowLodOptions::texels texels at the VPL's distance (On). The face comes from a uniform
// then instead of gl_InstanceID; alpha-tested materials stay one instanced draw of all faces.
#include "core/lights/vpl.h"
#include "core/mesh/hierarchy/mesh_clusters.h"
#include "core/scene/bounds.h"
#include "raster/context/shader_program.h"
#include "raster/scene/gpu_scene.h"
#include "raster/scene/material_glsl.h"
#include "raster/shadow/lod_provider.h"
#include "raster/shadow/shadow_lod.h"

#include <algorithm>
#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace irad::gl {

// The side an atlas (this one's, raster/shadow/ortho_atlas.h's) takes at most: kMaxAtlasSide
// (two 4096^2 depth textures are 128 MB), or this GL's texture or renderbuffer limit if smaller.
inline constexpr int kMaxAtlasSide = 4096;
int max_atlas_side(const GladGLContext& api);

class ShadowAtlas {
public:
  // Room for `blocks` blocks of resolution^2 faces, at most `batch` VPLs per render; throws
  // irad::Error when it exceeds this GL's texture, renderbuffer or uniform-block sizes.
  // features: the scene's (raster/scene/material_features.h); with alpha, absent fragments cast no
  // shadow.
  // lod: how the faces draw the opaque triangles (Off: all of them into every face). The
  // hierarchy comes from `shared` on the first render() (never for an animated scene); without
  // one the atlas builds its own then, of the scene it renders.
  // slots: the atlases drawn into in turn (below), at least 2.
  ShadowAtlas(const GladGLContext& api, int resolution, int batch, int blocks, const Bounds& bounds,
              const MaterialFeatures& features, const ShadowLodOptions& lod = {ShadowLodMode::Off},
              LodProvider* shared = nullptr, int slots = 2);

  // The largest batch (<= wanted) an atlas with one block per VPL can hold on this GL: 0 or 1
  // means batching is not possible.
  static int capacity(const GladGLContext& api, int resolution, int wanted);
  // A block's size in texels: 2R + 2h wide, 2h high, h = R/2 + 1 (see above).
  static glm::ivec2 block_size(int resolution) {
    const int h = resolution / 2 + 1;
    return {2 * resolution + 2 * h, 2 * h};
  }
  // Blocks a VPL takes: 1 for a surface VPL's hemisphere, 2 for a whole cube.
  static int blocks_for(const Vpl& vpl) { return vpl.kind == VplKind::Surface ? 1 : 2; }
  // A batch that holds a mirrored VPL draws the whole scene twice per face, without the
  // hierarchy (render below), so mirrored VPLs are batched apart: `vpls` in the order to batch
  // them, the mirrored ones last (else in their order), and whether b may follow a in a batch.
  static std::vector<const Vpl*> batch_order(std::vector<const Vpl*> vpls) {
    std::stable_partition(vpls.begin(), vpls.end(), [](const Vpl* v) { return v->mirror < 0; });
    return vpls;
  }
  static bool same_batch(const Vpl& a, const Vpl& b) { return (a.mirror < 0) == (b.mirror < 0); }

  // Clears the atlas and draws the cubes of vpls[0..n) (n <= batch(), their blocks_for summing to
  // at most blocks(); no directional VPLs). A mirrored VPL (core/scene/mirrors.h; the scene's
  // MaterialFeatures::mirrors) gets ShadowCube's unfolded cube; a batch with one draws the whole
  // scene twice per face, without the hierarchy. frames[s] receives the rotation world -> cube
  // frame of VPL s, blocks[s] the atlas texels of its first block (xy) and second block (zw).
  // Changes the bound framebuffer, viewport and program.
  void render(const Vpl* const* vpls, int n, const GpuScene& scene, std::vector<glm::mat3>& frames,
              std::vector<float>& fars, std::vector<glm::ivec4>& blocks);

  // Frees the atlases once other contexts draw the batches (raster/shadow/shadow_helpers.h):
  // texture() and gradient_texture() then name 1x1 textures, all a shading pass binds for a
  // batch without cubes, and render() throws.
  void release_atlases();
  // Draws the occluder planes from here on (ShadowLodOptions::planes On) where it was made
  // without them: a gradient texture beside each atlas. Changes the bound framebuffer.
  void enable_planes();

  // The atlas the last render() drew into.
  GLuint texture() const { return atlas_[current_].get(); }
  // Per texel the gradient of the distance / far per face texel (raster/glsl/cube_glsl.h).
  // 0 without ShadowLodOptions::planes (none made: a lookup reads no slope).
  GLuint gradient_texture() const { return gradient_[current_].get(); }
  int resolution() const { return resolution_; }
  int batch() const { return batch_; }
  const ShadowLodOptions& lod_options() const { return lod_options_; }
  int blocks() const { return grid_.x * grid_.y; }
  // Angular size of one texel at the centre of a face (radians), as ShadowCube::texel_angle.
  float texel_angle() const { return 2.0f / static_cast<float>(resolution_); }
  // Triangles the faces of the last render() drew from the hierarchy (0 without one), and the
  // hierarchy (nullptr before a render() or without one).
  std::size_t cluster_triangles() const { return cluster_triangles_; }
  const ShadowLod* lod() const { return lod_; }
  // Gets the hierarchy render() draws from (built now, in the current context, if not yet) and
  // returns its provider; nullptr when the faces draw every triangle.
  LodProvider* prepare_hierarchy(const GpuScene& scene) {
    return prepare_lod(scene) ? shared_lod_ : nullptr;
  }

  // Occlusion culling's rounds (below) serve only a batch whose faces picked at least this many
  // triangles per VPL: each readback waits for the GL (about 0.2 ms per VPL on llvmpipe, the
  // cost of some 2000 triangles), and culling takes 30 % on zdm2 (23k per VPL; a subdivided
  // Cornell box of 8k triangles, a few hundred per VPL, draws its shadows in 0.24 ms per VPL
  // without the rounds and 0.40-0.48 with them).
  static constexpr std::size_t kOcclusionTrianglesPerVpl = 8000;
  // The faces' draws are flushed to the GL whenever this many triangles were drawn since the
  // last flush: llvmpipe holds what it binned of a scene until the scene ends, so that the
  // memory a batch's atlas takes grows with the batch unless its scene is cut. Measured on the
  // 10M-triangle terrain (14.4k triangles per VPL, two helpers drawing batches of 107, 256x256,
  // peak resident set of runs in turn): 1407-1435 MiB unflushed, 1296-1320 MiB at 65,536,
  // 1195-1200 MiB in batches of 16 (which the helpers draw: BatchedPasses::kHelperBatch); no
  // slower (the 2.1M sphere box and zdm2 at 16,384).
  static constexpr std::size_t kFlushTriangles = 65536;

private:
  // One face of the batch: instance 6 s + f, its view-projection, rectangle and VPL position.
  struct Face {
    int instance;
    glm::mat4 view_projection;
    glm::vec4 rect;
    glm::vec3 origin;
    glm::ivec2 offset; // atlas texel - face texel
    float inv_far;
  };
  // With occlusion culling, a face draws its clusters nearest first in rounds, round r up to
  // this share of its triangles (the last: the rest), each after the depths of the rounds before
  // were read back (docs/performance.md measures the choice).
  static constexpr std::array<double, 3> kRounds = {0.25, 0.5, 1.0};
  // ... but only for a batch whose faces picked at least kOcclusionTrianglesPerVpl.
  // The hierarchy of `scene`, made on first use; false when the faces draw everything.
  bool prepare_lod(const GpuScene& scene);
  // The opaque triangles face by face from the hierarchy, the alpha-tested ones instanced; with
  // ShadowLodOptions::occlusion in two passes: every face's nearest clusters, then the rest that
  // the depths read back do not hide (raster/shadow/shadow_occlusion.h).
  void draw_clusters(int n, const GpuScene& scene);
  // Each face's cut through the hierarchy into picks_ (totals_: their indices), the deferred
  // levels the cuts want built first, round by round (ShadowLod::pick).
  void pick_faces();
  // picks_ nearest first in the rounds of kRounds, each culled against the rounds before.
  void draw_in_rounds();
  void sort_by_distance(const Face& f, std::vector<ClusterPick>& picks) const;
  // Moves the nearest of picks_[face] into `out` until the face's drawn triangles reach `share`
  // of its total.
  void take_nearest(std::size_t face, double share, std::vector<ClusterPick>& out);
  // Reads the atlas's depths back and drops from per_face what they hide.
  void cull_occluded(std::vector<std::vector<ClusterPick>>& per_face);
  // Draws each face's picks (per_face[i] for faces_[i], sorted on the way), one multi-draw per
  // face.
  void draw_faces(std::vector<std::vector<ClusterPick>>& per_face);
  // A gradient texture for atlas a, its framebuffer's colour attachment.
  void add_gradient(std::size_t a);
  glm::ivec2 block_origin(int b) const { return glm::ivec2(b % grid_.x, b / grid_.x) * block_; }

  const GladGLContext* api_;
  int resolution_, batch_;
  glm::ivec2 block_, grid_; // block size in texels; blocks per row, rows
  Bounds bounds_;
  ShaderProgram program_;
  MaterialUniforms material_;
  // Atlases drawn into in turn: the next batch's shadow maps need not wait for the shading passes
  // that read the last batch's (llvmpipe waits before it renders into a texture that a queued
  // draw samples; a helper's context waits for a fence: raster/shadow/shadow_helpers.h).
  std::vector<Texture> atlas_;
  std::vector<Texture> gradient_; // RG16F
  std::vector<Framebuffer> fbo_;
  std::size_t current_ = 0;
  Buffer block_buffer_;           // the ShadowBatch uniform block
  std::vector<float> block_data_; // its contents, filled per batch
  ShadowLodOptions lod_options_;
  GLint u_face_;
  GLint u_copies_; // -1: a scene without mirrors (the program has no mirrored cubes)
  LodProvider* shared_lod_;
  std::unique_ptr<LodProvider> own_lod_; // without a shared one
  const ShadowLod* lod_ = nullptr;       // from either, on the first render()
  // The scene's and the hierarchy's vertex arrays made in this atlas's context (which may be a
  // thread's of its own: raster/shadow/shadow_helpers.h).
  VertexArray scene_vao_, lod_vao_;
  ShadowLod::Plans plans_;
  std::vector<std::int32_t> wanted_; // nodes whose deferred levels a pick wants
  std::vector<Face> faces_;          // of the last render()
  ClusterSelection selection_;
  std::vector<std::vector<ClusterPick>> picks_, near_; // per face of faces_
  std::vector<std::size_t> totals_, taken_;            // per face: indices picked, taken
  std::vector<float> depth_;                           // the atlas read back (occlusion culling)
  std::size_t cluster_triangles_ = 0;
  std::size_t unflushed_ = 0; // triangles drawn since the last flush (kFlushTriangles)
};

} // namespace irad::gl
