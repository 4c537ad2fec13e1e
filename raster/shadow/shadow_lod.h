#pragma once
// The cluster hierarchy of core/mesh/hierarchy/mesh_clusters.h on the GPU, and the choice of what
// one shadow face draws: the nodes whose bounds meet the face's pyramid (clipped to the rectangle
// the face is ever looked up on), and of those the cut with the fewest triangles in which every
// mesh's error is below
//     max(error_per_distance * distance(VPL, node bounds), error_floor)
// (per node: the cheaper of its cheapest acceptable mesh and its children's plans; the original
// triangles are always acceptable).
// With error_per_distance = f * (2 / R), the angle of a texel at a face's centre times a factor
// f, a chosen node's mesh lies within f texels of the original surface as the VPL sees it.
// Culling is exact: a node is left out only when its box lies wholly outside a plane of the
// face's pyramid, where GL would clip all of it.
//
// On the GPU only the parts the faces draw: the hierarchy's indices in pages of kPageIndices
// (256 triangles), each copied on its first use (make_resident) from the hierarchy's indices (in
// memory after a build, in the cache file after a hit) into the next free slot of a list of
// index buffers (slabs of kSlabPages pages, made as they fill). The faces of a render draw a
// small part of the hierarchy: on the 10M-triangle terrain at 256x256 (1252 VPLs) 5.1 % of its
// 470 MiB of indices, in pages of 69 MiB; on the sphere box 4.4 % of 85 MiB, in 10 MiB (a
// buffer's store costs its whole size at creation: llvmpipe clears it). A face's ranges are
// drawn with one glMultiDrawElements per slab (ranges that touch are merged).
//
// Deferred levels (ClusterOptions::defer_levels): a node's coarser levels are built when a face
// first could draw one, that is where its own mesh is within the face's error (every level's
// error is at least the mesh's). pick() then stops at the node and names it; the caller builds
// the levels named (build_levels) and picks again, until no face names one: the cut is the one
// all levels built beforehand give, since a plan reads only the levels of nodes it visits and
// visits the same nodes once those have theirs. Their indices are appended after the
// hierarchy's (MeshClusters::late_indices), in pages of their own.
#include "core/mesh/hierarchy/mesh_clusters.h"
#include "raster/context/gl_objects.h"
#include "raster/scene/gpu_scene.h"

#include <glm/glm.hpp>
#include <mutex>
#include <shared_mutex>
#include <span>
#include <vector>

namespace irad::gl {

// One node's part of a face's cut: indices [first, first + count) of the hierarchy (its mesh, a
// coarser level or its original triangles), whose triangles lie in the node's bounds.
struct ClusterPick {
  std::uint32_t first = 0, count = 0;
  std::int32_t node = -1;
};

// What one face draws: per slab, index ranges of its buffer (byte offsets, as
// glMultiDrawElements takes them).
struct ClusterSelection {
  struct Slab {
    GLuint buffer = 0;
    std::vector<GLsizei> counts;
    std::vector<const void*> offsets;
  };
  std::vector<Slab> slabs; // by slab; those without ranges are skipped
  std::size_t triangles = 0;
  void clear() {
    for (Slab& s : slabs) {
      s.counts.clear();
      s.offsets.clear();
    }
    triangles = 0;
  }
};

// Appends the range of `count` indices at index `first` of a slab to `out`, merged with its last
// range when they touch.
void add_range(std::size_t first, std::size_t count, ClusterSelection::Slab& out);

// The four planes a * p + d >= 0 of the pyramid that face pixels p of [x0, x1] x [y0, y1]
// (rect) see through the face view-projection `view_projection` (R texels per edge):
// pixel = (ndc + 1) R / 2, as the batched shadow vertex shader computes it.
std::array<glm::vec4, 4> face_planes(const glm::mat4& view_projection, const glm::vec4& rect,
                                     int resolution);

class ShadowLod {
public:
  static constexpr std::size_t kPageIndices = 768; // 3 KiB, 256 triangles
  static constexpr std::size_t kSlabPages = 4096;  // 12 MiB per buffer

  // Keeps `clusters` (of gpu's scene) for the pages the faces will draw; none is on the GPU yet.
  // `simplify`: whether the inner nodes' meshes may be drawn (false: culling only, the original
  // triangles).
  // slab_pages: the pages per buffer (tests take fewer).
  ShadowLod(const GladGLContext& api, const GpuScene& gpu, MeshClusters clusters, bool simplify,
            std::size_t slab_pages = kSlabPages);

  // Copies the pages `picks` draw that no call copied before, from any thread whose context
  // shares this one's objects (one call at a time). Once other contexts draw from this hierarchy
  // (share_with_contexts), a call that copied any returns after glFinish, so that a draw in
  // another context, which binds the buffers again (draw()), sees them; before, the copies are
  // ordered with the calling context's own draws and nothing waits (a glFinish drains
  // llvmpipe's queue of binned passes, leaving its rasterizer threads idle while this thread
  // bins the next ones). Throws Error when the cache file changed since it was checked.
  void make_resident(const std::vector<std::vector<ClusterPick>>& picks) const;
  // From now on other contexts (raster/shadow/shadow_helpers.h) draw from this hierarchy: the
  // pages copied so far are made visible to them (glFinish in the calling context, the one that
  // copied them), and make_resident finishes after each copy.
  void share_with_contexts() const;
  // The ranges of `picks` (made resident) in the slabs.
  void select(const std::vector<ClusterPick>& picks, ClusterSelection& out) const;

  // A node's plan for one face (pick()): a range of indices, or its children's plans.
  struct Choice {
    std::uint32_t first = 0, count = 0; // count: the triangles of the plan (0: nothing)
    bool children = false;
  };
  // pick()'s plans, per node: the caller's, so that threads pick at once.
  using Plans = std::vector<Choice>;

  // Appends to `out`, node by node in depth-first order, the cut of the face with pyramid
  // `planes` seen from `origin` (for occlusion culling: raster/shadow/shadow_occlusion.h).
  // error_floor: an error no shadow test can tell (far below the depth bias), so that coplanar
  // simplification, exact up to rounding, serves even a VPL inside a node's bounds.
  // wanted: gets the nodes whose deferred levels the cut needs (then `out` is not the cut:
  // build_levels(*wanted), and pick again); nullptr: such nodes are planned without levels.
  void pick(const std::array<glm::vec4, 4>& planes, const glm::vec3& origin,
            float error_per_distance, float error_floor, Plans& plans,
            std::vector<ClusterPick>& out, std::vector<std::int32_t>* wanted = nullptr) const {
    pick(clusters_.roots, planes, origin, error_per_distance, error_floor, plans, out, wanted);
  }
  // The same over the trees of `roots` alone (some of clusters().roots).
  void pick(std::span<const std::int32_t> roots, const std::array<glm::vec4, 4>& planes,
            const glm::vec3& origin, float error_per_distance, float error_floor, Plans& plans,
            std::vector<ClusterPick>& out, std::vector<std::int32_t>* wanted = nullptr) const;
  // Builds the deferred levels of `nodes` (core/mesh/hierarchy/cluster_levels.h
  // add_deferred_levels, on all cores) that are still pending, from any thread (one build at a
  // time; picks wait for it).
  void build_levels(const std::vector<std::int32_t>& nodes) const;
  // The nodes whose deferred levels build_levels built, and the seconds it took.
  struct LateLevels {
    std::size_t nodes = 0;
    double seconds = 0.0;
  };
  LateLevels late_levels() const;
  // A vertex array of the current context over the scene's vertices and this hierarchy's
  // indices (vertex arrays are not shared between contexts): what draw() draws through.
  // (Its element buffer is bound per slab by draw().)
  VertexArray vertex_array() const { return gpu_->vertex_array_with(Buffer{}); }
  // Draws `selection` through `vao` (the bound program's state is the caller's); its ranges
  // must have been made resident.
  void draw(const ClusterSelection& selection, const VertexArray& vao) const;

  // Every triangle of the scene that is not in the hierarchy (Mask and Blend materials) has to be
  // drawn by the caller. Its `triangles` list is not kept (the cache's record, which no pass
  // reads: 40 MiB at 10M triangles), and its indices are all behind `stored_indices` (a build's
  // moved there), never in `indices`.
  const MeshClusters& clusters() const { return clusters_; }
  // The bytes of the slabs made so far.
  std::size_t gpu_bytes() const;

private:
  struct Query {
    const std::array<glm::vec4, 4>* planes;
    glm::vec3 origin;
    float error_per_distance, error_floor;
    Plans* plans;
    std::vector<std::int32_t>* wanted;
  };
  // A node's acceptable mesh of at most this many triangles is taken without a look below.
  static constexpr std::uint32_t kSmallEnough = 64;
  std::uint32_t plan(std::int32_t id, const Query& q) const;
  void emit_plan(std::int32_t id, const Plans& plans, std::vector<ClusterPick>& out) const;

  // Copies `count` pages from page `page` into consecutive slots from `slot` (in one slab; all
  // of the hierarchy's indices or all late ones).
  void copy_pages(std::size_t page, std::size_t slot, std::size_t count) const;
  // The first page of the late indices (MeshClusters::late_base).
  std::size_t late_page() const { return clusters_.late_base() / kPageIndices; }
  // The slab for `slot`, made when it is the first slot of a new one.
  GLuint slab_of(std::size_t slot) const;
  // The slots free from the next (slots_used_, moved to the next slab's first where its slab is
  // full) to its slab's end.
  std::size_t free_slots() const;

  const GladGLContext* api_;
  const GpuScene* gpu_;
  // Its indices all behind stored_indices: the source of the pages (late ones: late_indices).
  // Its levels grow (build_levels) under levels_mutex_, which plans and copies read it under.
  mutable MeshClusters clusters_;
  mutable std::shared_mutex levels_mutex_;
  mutable LateLevels late_;
  std::size_t index_count_ = 0; // of the hierarchy, before the late indices
  bool simplify_;
  std::size_t slab_pages_;
  mutable std::mutex pages_mutex_;                  // guards what follows
  mutable std::vector<std::uint32_t> slot_of_page_; // its slot + 1; 0: not on the GPU
  mutable std::vector<Buffer> slabs_;
  mutable std::vector<std::size_t> slab_capacity_; // pages per slab
  mutable std::size_t slots_used_ = 0;             // slots before the next free one
  mutable std::size_t pages_copied_ = 0;
  mutable bool shared_ = false; // share_with_contexts() was called
};

} // namespace irad::gl
