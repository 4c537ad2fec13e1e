#pragma once
// A cluster hierarchy with levels of detail over a scene's opaque triangles, for the shadow
// passes (raster/shadow/shadow_lod.h): they cull it against each cube face and draw, per face, a
// cut through it whose geometric error stays below the shadow map's texel at the VPL's distance.
//
// The base: with ClusterOptions::simplify, the triangles after the exact planar reduction
// (core/mesh/planar/planar_reduction.h: flat parts down to what their outlines need, within 2e-6 of
// the scene's diagonal, which is the leaves' error) of the components that have flat parts
// (core/mesh/planar/flat_components.h); without, the scene's own triangles (error 0).
// Without it, a region cut through a finely tessellated wall keeps its border at the full
// resolution in every level above: thousands of triangles per face on the 2.1M-triangle flat
// scale scene (docs/performance.md).
//
// The tree: a binary tree of spatial regions (split by the surface-area heuristic over the
// base triangles' centroids) down to leaves of at most ClusterOptions::leaf_triangles
// triangles. Every node has a mesh: a leaf its base triangles, an inner node the union of its
// children's meshes simplified to half their triangles (meshoptimizer, meshopt_SimplifyLockBorder)
// with
//     error(node) = max(error(children)) + meshopt's result_error * meshopt_simplifyScale,
// a world-space bound on how far its mesh lies from the original surface (meshoptimizer's
// quadric estimate; tests/test_shadow_lod.cpp measures it). Errors grow toward the root. Each
// node also keeps coarser levels of its own mesh, its region's border simplified with it (error:
// the level before's plus 2.5 times meshoptimizer's estimate of the step, which weighs a
// border's sag less than the surface's): halved again and again, for the faces that see it from
// far (leaves of large scenes keep none: leaf_levels); where the first halving needs no error
// (coplanar triangles), that level goes as far as meshoptimizer gets without error.
//
// The trees: one per large connected component (welded), and one for all the small ones. A
// component's root also keeps levels of the whole component, with only the component's own open
// edges locked: a face that sees the component from far draws one of them (one mesh, no seams),
// one that sees it from near a cut of its tree. They are simplified from the cut through the
// nodes two above the leaves (about a quarter of the triangles; error: the largest of those
// nodes'), in a fifth of the time the original triangles take (scripts/make_large_glb.py's
// 2M-triangle terrain: 0.65 s against 3.7 s). In tests/test_shadow_lod.cpp the faces of 16 VPLs
// of a Cornell box with a sphere draw 20,071 triangles (15.3M without the hierarchy), and a render
// with the simplified shadows stays within relMSE 1.33e-5 of the full meshes'.
//
// The base meshes are crack-free by construction: a node's open edges, the border of its region,
// are locked in its simplification, and every region's border is part of the borders of the
// regions below it that touch it, so every node's mesh keeps its region's original border
// exactly. Any cut of base meshes (a set of nodes whose regions tile the mesh) therefore meets
// along original edges. A coarser level simplifies its border too, so where a cut draws two
// neighbours at different levels a crack may open along their border, at most their two errors
// wide: below a texel where the shadow faces draw them (half a texel each). Locked, a level could
// not drop below its border's length in triangles, and the cut of a finely tessellated surface
// seen from near (a VPL on a terrain) grows with the tessellation (docs/performance.md "Shadow
// maps against scene size"). Simplification keeps topology (edge collapses onto existing
// vertices), so a closed surface stays closed.
//
// The meshes index the scene's own vertex array, so a GPU draws them with the scene's vertex
// buffer. Positions are welded first (vertices at one position become the first of them: the
// simplifier sees one connected surface where a file or subdivide() duplicated vertices at
// seams); a welded index draws the same position, so without simplify the leaves draw the very
// triangles the scene has.
#include "core/mesh/hierarchy/stored_indices.h"
#include "core/scene/bounds.h"
#include "core/scene/scene.h"
#include "core/util/stage_times.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace irad {

// How the batched shadow passes use the hierarchy (RasterOptions::shadow_lod).
enum class ShadowLodMode {
  Off,  // every triangle into every face (the reference)
  Cull, // only the clusters a face sees: exact, the same image
  On,   // culled, and each face draws the coarsest nodes whose error is below its texel
};
enum class ShadowPlanes { Auto, On, Off };
// Whether the raster's G-buffer and emitters draw through the camera's hierarchy
// (RasterOptions::camera_lod).
enum class CameraLodMode { Off, On };
struct ShadowLodOptions {
  ShadowLodMode mode = ShadowLodMode::On;
  // On: the error a drawn level may have, in texels at the centre of a face at the cluster's
  // distance (docs/performance.md measures the image error against it).
  float texels = 0.5f;
  // Cull and On: a face draws its nearest clusters first and leaves out those the depths then
  // stored hide (exact: the same image; raster/shadow/shadow_occlusion.h).
  bool occlusion = true;
  // The batched passes' occluder planes (raster/glsl/cube_glsl.h): a gradient per shadow texel,
  // so that thin walls seen at an angle hold (docs/accuracy.md); off: the centre's distance
  // alone, 11-16 % more VPLs/s on llvmpipe's Cornell box at 512x512 and light through walls
  // thinner than a texel's depth range. Auto: on where the scene's thinnest wall
  // (walk/walls/thin_walls.h) is thin enough for the faces' resolution (raster_renderer.h
  // planes_needed); the raster, which cannot measure walls, takes Auto for On unless given
  // RasterOptions::choose_planes, which irad::render gives (the scan, asked when shadow maps are
  // first drawn to shade). (The per-VPL reference passes keep them.)
  ShadowPlanes planes = ShadowPlanes::Auto;
  // On: each node's coarser levels built when a face first could draw one
  // (ClusterOptions::defer_levels; raster/shadow/shadow_lod.h); false: all with the hierarchy.
  // The same shadows either way.
  bool levels_on_demand = true;
};

// A coarser level of a node: indices [first, first + count), error as ClusterNode::error.
// (For a component's root: relative to the original triangles, so not always above `error`.)
struct ClusterLevel {
  float error = 0.0f;
  std::uint32_t first = 0, count = 0;
};

struct ClusterNode {
  Bounds bounds;      // of the region's original triangles; every node below lies inside
  float error = 0.0f; // world-space distance of the mesh from the original surface (0: a leaf)
  // The node's mesh: indices [mesh_first, mesh_first + mesh_count) of MeshClusters::indices.
  std::uint32_t mesh_first = 0, mesh_count = 0;
  // The region's original triangles: indices [leaf_first, leaf_first + leaf_count), inside the
  // original part (the leaves below, contiguous in depth-first order).
  std::uint32_t leaf_first = 0, leaf_count = 0;
  std::int32_t children[2] = {-1, -1};
  // Its coarser levels: MeshClusters::levels [levels_first, levels_first + levels_count),
  // errors ascending, triangles descending; levels_first kPendingLevels (count 0): not built yet
  // (ClusterOptions::defer_levels; add_deferred_levels builds them). A pending node is never a
  // component's root, so every level it will have has an error of at least `error`.
  static constexpr std::uint32_t kPendingLevels = ~0u;
  std::uint32_t levels_first = 0, levels_count = 0;
  bool leaf() const { return children[0] < 0; }
  bool levels_pending() const { return levels_first == kPendingLevels; }
};

// Where the levels built after the hierarchy (add_deferred_levels) start in its index space:
// MeshClusters::late_indices are indices [late_base(), late_base() + late_indices.size()), and
// each call's start on a multiple of this (a multiple of the shadow passes' page,
// raster/shadow/shadow_lod.h: a page the GPU copied never grows).
inline constexpr std::size_t kLateAlign = 768;

struct MeshClusters {
  std::vector<std::uint32_t> indices; // into Scene::positions, 3 per triangle
  // Through the cache (a hit, or a write) `indices` is empty: they stay in its file, from which
  // the shadow passes copy the pages they draw (core/mesh/hierarchy/stored_indices.h).
  std::shared_ptr<const StoredIndices> stored_indices;
  std::size_t index_count() const {
    return stored_indices ? stored_indices->size() : indices.size();
  }
  // The indices of the levels built after the hierarchy (deferred ones), in memory; see
  // kLateAlign. Their levels follow the others' in `levels`.
  std::vector<std::uint32_t> late_indices;
  std::size_t late_base() const {
    return (index_count() + kLateAlign - 1) / kLateAlign * kLateAlign;
  }
  // The end of the index space: past the late indices where there are any.
  std::size_t index_end() const {
    return late_indices.empty() ? index_count() : late_base() + late_indices.size();
  }
  // Where levels are deferred (ClusterOptions::defer_levels): the build's max_levels and step,
  // which add_deferred_levels builds them with; 0 where no node is pending.
  int deferred_max_levels = 0, deferred_step = 0;
  // The nodes whose levels add_deferred_levels built (or a cache's late file gave), in the order
  // they were: their levels are those with indices in late_indices.
  std::vector<std::int32_t> late_nodes;
  std::vector<ClusterNode> nodes; // every tree's nodes, parents before children
  // The trees' roots: one per connected component of at least ClusterOptions::leaf_triangles
  // triangles (its coarser levels simplify the whole component, from its original triangles,
  // with no region border inside it locked), one for all smaller components together. Empty
  // when no triangle is clustered.
  std::vector<std::int32_t> roots;
  std::vector<ClusterLevel> levels; // the nodes' coarser levels
  // indices[0, original_indices): the base, every clustered triangle once (welded; with
  // simplify their planar reduction), leaves in depth-first order; the simplified meshes of the
  // inner nodes and the coarser levels follow.
  std::size_t original_indices = 0;
  // The scene triangles in the hierarchy (those of Opaque materials), ascending, where some are
  // left out; empty where every triangle of the scene is in it (or none is: roots is empty too).
  // (A list of every triangle would hold 40 MB at 10M triangles into the passes, at their peak.)
  std::vector<std::uint32_t> triangles;
  // A camera hierarchy's (ClusterOptions::camera): the material of roots[k]'s triangles, one per
  // root; empty for the shadow passes' (their trees mix materials).
  std::vector<std::uint32_t> root_materials;
  std::size_t bytes() const {
    return (indices.size() + late_indices.size()) * sizeof(std::uint32_t) +
           nodes.size() * sizeof(ClusterNode) + levels.size() * sizeof(ClusterLevel) +
           (triangles.size() + root_materials.size()) * sizeof(std::uint32_t);
  }
};

struct ClusterOptions {
  // At most this many per leaf; 0: automatic_leaf_triangles. Smaller leaves cull tighter
  // against a face's pyramid and the depths already drawn, larger ones leave fewer region
  // borders, which every base mesh keeps exactly (docs/performance.md measures both).
  std::uint32_t leaf_triangles = 0;
  // false: the base is the scene's triangles and inner nodes' meshes are their leaves' (the
  // Cull mode: the same image as drawing every triangle).
  bool simplify = true;
  int max_levels = 8; // coarser levels per node at most
  // The components' roots get their coarser levels in the build, and other nodes only while a
  // root's task still runs (cores that would otherwise wait; which nodes, depends on the timing,
  // their levels do not); every other node's wait (ClusterNode::levels_pending) until a shadow
  // face could draw one (raster/shadow/shadow_lod.h builds them then, with add_deferred_levels:
  // the same levels). Many of a big scene's nodes are never seen from far enough for a level: the
  // 10M-triangle terrain's faces at 256x256 build the levels of 1,074-1,236 of its about 13,000
  // pending nodes (docs/performance.md "Big scenes").
  bool defer_levels = false;
  // Threads of the build (0: all cores); the hierarchy is the same on any number (with
  // defer_levels, which nodes' levels come with it depends on the timing; the levels do not).
  unsigned threads = 0;
  // The camera passes' hierarchy (raster/passes/camera_lod.h), which draws every attribute, not
  // only positions: vertices welded only where all their attributes are equal (a seam of
  // normals or texture coordinates stays open, and meshoptimizer keeps it), one tree per
  // material and connected component (a draw binds one material), no planar reduction and no
  // coarser levels (their borders move: a cut of base meshes alone is crack-free, and a crack
  // in the camera's image would show what lies behind). An inner node's error is the larger of
  // its distance from the surface and its mesh's longest edge (meshoptimizer weighs positions
  // alone, so the edge bounds how far the normals are interpolated). `simplify` and
  // `max_levels` are not read.
  bool camera = false;
};

// About 512 leaves, 128 to 1024 triangles each (a power of two). On zdm2 (58k triangles,
// 256x256, 64^2 faces) leaves of 128 leave 16k triangles per VPL against 33k with 1024; on the
// 2.1M-triangle scale scenes 1024 draw their shadows in half the time of 128 (the borders).
std::uint32_t automatic_leaf_triangles(std::size_t triangles);

// The step between a node's coarser levels (add_coarser_levels,
// core/mesh/hierarchy/cluster_levels.h): a quarter from leaves of kQuarteringLeaf triangles (the
// automatic leaves of scenes over 512k triangles), else a half. Cold renders at 256x256, quarters
// against halves (one run each, in turn): the levels of the 2.1M sphere box 1.01 against 1.29 s
// (986 against 946 shadow triangles per VPL), of the 2M terrain 1.25 against 1.53 s (12,509 against
// 13,263), of the 10M terrain 5.83 against 7.77 s (14,355 against 14,386; its whole render 20.1
// against 25.1 s); images within 3.5e-8 relMSE of each other. On zdm2's leaves of 128 quarters drew
// 16,762 triangles per VPL against 16,037: small scenes keep halves.
inline constexpr std::uint32_t kQuarteringLeaf = 1024;
int level_step(std::uint32_t leaf_triangles);

// Whether leaves keep coarser levels: not those of kQuarteringLeaf triangles, whose levels cost
// half of the levels' build (the original triangles, quartered) for few triangles drawn: a face
// that would draw a leaf's level draws its parent's mesh or levels instead. Levels stage of the
// build alone (2 threads), with leaf levels against without, and shadow triangles per VPL at
// 256x256: the 2.1M sphere box 1.05-1.29 against 0.59-0.67 s, 986 against 1,052; the 2M terrain
// 12,509 against 13,703; in cold renders the 10M terrain 5.61 against 3.33 s, 14,355 against
// 15,685, the 10M sphere box 2.14 against 1.21 s, 1,032 against 1,079. The warm 2.1M sphere box's
// raster stage stayed within the noise (1.14-1.42 against 1.16-1.41 s, four pairs), its image
// within 2e-18 relMSE. Smaller leaves keep them: zdm2's would draw 17,243 triangles per VPL
// against 16,037, the textured 205k terrain's 10,540 against 9,812, for 0.04-0.13 s of build.
bool leaf_levels(std::uint32_t leaf_triangles);

// The hierarchy over the triangles of Opaque materials (Mask and Blend ones keep their alpha
// test, drawn apart by the caller). The caller decides about animated scenes (the tree is of the
// positions at the time of the call).
// times: where given, gets the build's stages (weld, planar, tree, inner, levels).
MeshClusters build_mesh_clusters(const Scene& scene, const ClusterOptions& options = {},
                                 StageTimes* times = nullptr);

// The hierarchy the batched shadow passes draw with `lod` (mode Cull or On): Cull the scene's
// own triangles (the same image as Off), On also their reductions and levels.
ClusterOptions shadow_cluster_options(const ShadowLodOptions& lod);

// The distance from p to the box b (0 inside).
float distance_to(const Bounds& b, const glm::vec3& p);

} // namespace irad
