// The shadow passes' cluster hierarchy (core/mesh/hierarchy/mesh_clusters.h) and its use by the
// batched shadow atlas (raster/shadow/shadow_lod.h, RasterOptions::shadow_lod): the tree's
// invariants on the CPU, culling that changes no pixel, and the level of detail against the full
// meshes. With IRAD_TEST_IMAGES=DIR the GL tests write their images to DIR.
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/image/image_metrics.h"
#include "core/mesh/hierarchy/cluster_cache.h"
#include "core/mesh/hierarchy/mesh_clusters.h"
#include "core/mesh/sphere_mesh.h"
#include "core/scene/scene_builder.h"
#include "raster/context/gl_context.h"
#include "raster/raster_renderer.h"
#include "raster/scene/gpu_scene.h"
#include "raster/shadow/shadow_atlas.h"
#include "raster/shadow/shadow_lod.h"
#include "tests/shadow_lod_support.h"
#include "tests/side_by_side.h"
#include "tests/test_paths.h"
#include "tests/test_rooms.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/vpls/quasi_random_walk.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>
#include <map>
#include <random>
#include <unistd.h>
#include <utility>

namespace irad {
namespace IRAD_UNITY_ID {

Log quiet_log() {
  return Log([](const std::string&) {});
}

double mean_rgb(const Image& image) {
  double sum = 0.0;
  for (const glm::vec4& p : image.pixels()) sum += double(p.r) + p.g + p.b;
  return sum / (3.0 * static_cast<double>(image.pixels().size()));
}

constexpr glm::vec3 kCentre{0.1f, -0.2f, 0.3f};
constexpr float kRadius = 2.0f;

Scene sphere_scene(int rings) {
  Scene s;
  add_sphere(s, kCentre, kRadius, rings, add_material(s, glm::vec3(0.5f)));
  finish(s);
  return s;
}

// The welded triangles of mesh [first, first + count) of c, each sorted (orientation apart).
std::vector<std::array<std::uint32_t, 3>>
sorted_triangles(const MeshClusters& c, std::uint32_t first, std::uint32_t count) {
  std::vector<std::array<std::uint32_t, 3>> out;
  for (std::uint32_t k = first; k < first + count; k += 3) {
    std::array<std::uint32_t, 3> t{c.indices[k], c.indices[k + 1], c.indices[k + 2]};
    std::sort(t.begin(), t.end());
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(ShadowLod, EveryTriangleInExactlyOneLeaf) {
  const Scene s = sphere_scene(64); // 16128 triangles
  const MeshClusters c = build_mesh_clusters(s, {256, true});
  ASSERT_FALSE(c.nodes.empty());
  EXPECT_TRUE(c.triangles.empty()); // every triangle is in it
  EXPECT_EQ(c.original_indices, 3 * s.triangle_count());
  // The leaves' ranges tile the original part in depth-first order.
  std::uint32_t next = 0;
  for (const ClusterNode& n : c.nodes) {
    if (!n.leaf()) continue;
    EXPECT_EQ(n.leaf_first, next);
    EXPECT_LE(n.leaf_count, 3u * 256u);
    next += n.leaf_count;
  }
  EXPECT_EQ(next, c.original_indices);
  EXPECT_EQ(c.nodes[0].leaf_count, c.original_indices);
  // The original part is the scene's triangles (the sphere shares its vertices: no welding).
  std::vector<std::array<std::uint32_t, 3>> scene;
  for (const glm::uvec3& t : s.triangles) {
    std::array<std::uint32_t, 3> a{t.x, t.y, t.z};
    std::sort(a.begin(), a.end());
    scene.push_back(a);
  }
  std::sort(scene.begin(), scene.end());
  EXPECT_EQ(sorted_triangles(c, 0, static_cast<std::uint32_t>(c.original_indices)), scene);
}

TEST(ShadowLod, BoundsHoldTheirMeshesAndErrorsGrowTowardTheRoot) {
  const Scene s = sphere_scene(64);
  const MeshClusters c = build_mesh_clusters(s, {256, true});
  for (const ClusterNode& n : c.nodes) {
    for (std::uint32_t k = n.mesh_first; k < n.mesh_first + n.mesh_count; ++k) {
      const glm::vec3 p = s.positions[c.indices[k]];
      EXPECT_TRUE(glm::all(glm::lessThanEqual(n.bounds.lo, p)) &&
                  glm::all(glm::lessThanEqual(p, n.bounds.hi)));
    }
    if (n.leaf()) {
      EXPECT_EQ(n.error, 0.0f);
      continue;
    }
    for (std::int32_t k : n.children) {
      const ClusterNode& child = c.nodes[static_cast<std::size_t>(k)];
      EXPECT_GE(n.error, child.error);
      EXPECT_TRUE(glm::all(glm::lessThanEqual(n.bounds.lo, child.bounds.lo)) &&
                  glm::all(glm::lessThanEqual(child.bounds.hi, n.bounds.hi)));
    }
  }
  // The root of a closed surface (no border to lock) simplifies far down.
  EXPECT_LT(c.nodes[0].mesh_count / 3, s.triangle_count() / 16);
}

// meshoptimizer's error against the true distance: every vertex of a node's mesh lies on the
// sphere (simplification keeps vertices), so how far the mesh strays is the sag of its
// triangles, R - |centroid - centre| (about the largest over a flat triangle). Measured: the sag
// beyond the original tessellation's up to 1.4 times the node's error (meshoptimizer's quadric
// error is an area-weighted mean, not a maximum); ShadowLodOptions::texels (half a texel) leaves
// room for that. On the Cornell box with a sphere, the largest distance of sample points (the
// centroid and edge midpoints of every simplified triangle) from the node's original triangles
// is up to 2.7 times the error on the smallest nodes, 0.8 times on the root.
// Leaves of 256 triangles step a node's levels by halves, of kQuarteringLeaf by quarters (the
// mean ratio of a level's triangles to the one before it: measured 0.40 and 0.17; the
// component roots quarter either way).
void expect_error_bounds_the_distance(std::uint32_t leaf, double ratio_lo, double ratio_hi) {
  const Scene s = sphere_scene(64);
  const MeshClusters c = build_mesh_clusters(s, {leaf, true});
  // The original tessellation's own sag (the LOD adds to it).
  double sag0 = 0.0, worst = 0.0;
  for (std::uint32_t k = 0; k < c.original_indices; k += 3) {
    const glm::vec3 m = (s.positions[c.indices[k]] + s.positions[c.indices[k + 1]] +
                         s.positions[c.indices[k + 2]]) /
                        3.0f;
    sag0 = std::max(sag0, double(kRadius - glm::length(m - kCentre)));
  }
  const auto sag_of = [&](std::uint32_t first, std::uint32_t count) {
    double sag = 0.0;
    for (std::uint32_t k = first; k < first + count; k += 3) {
      const glm::vec3 m = (s.positions[c.indices[k]] + s.positions[c.indices[k + 1]] +
                           s.positions[c.indices[k + 2]]) /
                          3.0f;
      sag = std::max(sag, double(kRadius - glm::length(m - kCentre)));
    }
    return sag;
  };
  double worst_level = 0.0, ratios = 0.0;
  std::size_t levels = 0, steps = 0;
  for (const ClusterNode& n : c.nodes) {
    // The coarser levels, their region's border simplified too.
    for (std::uint32_t l = n.levels_first; l < n.levels_first + n.levels_count; ++l, ++levels) {
      const ClusterLevel& level = c.levels[l];
      worst_level = std::max(worst_level, (sag_of(level.first, level.count) - sag0) /
                                              std::max(double(level.error), 1e-9));
      if (l > n.levels_first) {
        ratios += double(level.count) / double(c.levels[l - 1].count);
        ++steps;
      }
    }
    if (n.leaf() || n.mesh_count == 0) continue;
    worst = std::max(worst,
                     (sag_of(n.mesh_first, n.mesh_count) - sag0) / std::max(double(n.error), 1e-9));
  }
  const double ratio = ratios / double(std::max<std::size_t>(steps, 1));
  std::printf("sphere 64 rings, leaves of %u: original sag %.3g, worst (sag - original) / error "
              "%.3g, of %zu coarser levels %.3g, level to level %.2f\n",
              leaf, sag0, worst, levels, worst_level, ratio);
  EXPECT_LT(worst, 2.0);
  EXPECT_GT(levels, 10u);
  EXPECT_LT(worst_level, 2.0);
  EXPECT_GT(ratio, ratio_lo);
  EXPECT_LT(ratio, ratio_hi);
}

TEST(ShadowLod, ErrorBoundsTheDistanceFromTheSurface) {
  expect_error_bounds_the_distance(256, 0.3, 0.6);
  expect_error_bounds_the_distance(kQuarteringLeaf, 0.08, 0.28);
}

// Any cut through the tree (here mixed levels) closes the sphere: every edge used as often in one
// direction as in the other (the cut's triangles have no boundary), so no shadow face sees a
// gap. (Not always manifold: where two regions' borders run a -> m -> b, each may fill the
// notch with a triangle a m b of its own, two coincident faces, closed either way.)
TEST(ShadowLod, AnyCutIsWatertight) {
  const Scene s = sphere_scene(64);
  const MeshClusters c = build_mesh_clusters(s, {256, true});
  std::uint32_t hash = 12345u;
  std::vector<std::int32_t> stack{0};
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  std::size_t triangles = 0, levels = 0;
  while (!stack.empty()) {
    const std::int32_t id = stack.back();
    const ClusterNode& n = c.nodes[static_cast<std::size_t>(id)];
    stack.pop_back();
    hash = hash * 1664525u + 1013904223u;
    // A quarter of the inner nodes below the root taken whole.
    if (n.leaf() || (id != 0 && (hash >> 30) == 0)) {
      levels += n.leaf() ? 0 : 1;
      for (std::uint32_t k = n.mesh_first; k < n.mesh_first + n.mesh_count; k += 3) {
        ++triangles;
        for (int e = 0; e < 3; ++e) ++directed[{c.indices[k + e], c.indices[k + (e + 1) % 3]}];
      }
      continue;
    }
    stack.push_back(n.children[0]);
    stack.push_back(n.children[1]);
  }
  EXPECT_GT(levels, 2u);
  EXPECT_LT(triangles, s.triangle_count());
  std::size_t open = 0;
  for (const auto& [edge, count] : directed) {
    const auto back = directed.find({edge.second, edge.first});
    if (back == directed.end() || back->second != count) ++open;
  }
  EXPECT_EQ(open, 0u);
}

TEST(ShadowLod, AlphaTestedTrianglesStayOutOfTheTree) {
  Scene s;
  const std::uint32_t opaque = add_material(s, glm::vec3(0.5f));
  const std::uint32_t masked = add_material(s, glm::vec3(0.5f));
  s.materials[masked].alpha_mode = AlphaMode::Mask;
  add_quad(s, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, opaque);
  add_quad(s, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, masked);
  finish(s);
  const MeshClusters c = build_mesh_clusters(s);
  EXPECT_EQ(c.triangles, (std::vector<std::uint32_t>{0, 1}));
  EXPECT_EQ(c.original_indices, 6u);
}

// Whether a and b hold the same hierarchy, field by field (floats bit for bit).
bool same_hierarchy(const MeshClusters& a, const MeshClusters& b) {
  const auto same_node = [](const ClusterNode& x, const ClusterNode& y) {
    return x.bounds.lo == y.bounds.lo && x.bounds.hi == y.bounds.hi && x.error == y.error &&
           x.mesh_first == y.mesh_first && x.mesh_count == y.mesh_count &&
           x.leaf_first == y.leaf_first && x.leaf_count == y.leaf_count &&
           x.children[0] == y.children[0] && x.children[1] == y.children[1] &&
           x.levels_first == y.levels_first && x.levels_count == y.levels_count;
  };
  const auto same_level = [](const ClusterLevel& x, const ClusterLevel& y) {
    return x.error == y.error && x.first == y.first && x.count == y.count;
  };
  return a.indices == b.indices && a.roots == b.roots && a.triangles == b.triangles &&
         a.original_indices == b.original_indices &&
         std::equal(a.nodes.begin(), a.nodes.end(), b.nodes.begin(), b.nodes.end(), same_node) &&
         std::equal(a.levels.begin(), a.levels.end(), b.levels.begin(), b.levels.end(), same_level);
}

// The build runs its nodes' simplifications in parallel; the result must not depend on how
// many threads did: two spheres (two component trees with their whole-component levels) and
// small ones (the tree of the small components), on 1, 2 and 3 threads.
TEST(ShadowLod, TheSameHierarchyOnAnyNumberOfThreads) {
  Scene s;
  add_sphere(s, kCentre, kRadius, 48, add_material(s, glm::vec3(0.5f)));
  add_sphere(s, kCentre + glm::vec3(5.0f, 0.0f, 0.0f), 1.0f, 32, add_material(s, glm::vec3(0.5f)));
  for (int k = 0; k < 20; ++k) // 48 triangles each
    add_sphere(s, glm::vec3(float(k), -4.0f, 0.0f), 0.3f, 4, add_material(s, glm::vec3(0.5f)));
  finish(s);
  ClusterOptions options{128, true};
  options.threads = 1;
  StageTimes stages;
  const MeshClusters one = build_mesh_clusters(s, options, &stages);
  ASSERT_GE(one.roots.size(), 3u);
  std::vector<std::string> names;
  for (const auto& stage : stages.stages()) names.push_back(stage.first);
  EXPECT_EQ(names, (std::vector<std::string>{"weld", "planar", "tree", "inner", "levels"}));
  for (unsigned threads : {2u, 3u}) {
    options.threads = threads;
    EXPECT_TRUE(same_hierarchy(one, build_mesh_clusters(s, options))) << threads << " threads";
  }
}

// ---------------------------------------------------------------------------------------------
// GL: the Cornell box with a finely tessellated sphere floating in it.

Scene cornell_with_sphere(int rings) {
  Log log = quiet_log();
  Scene s = load_gltf(std::filesystem::path(IRAD_SOURCE_DIR) / "data/cornell_box.gltf", log);
  add_sphere(s, {0.3f, 0.33f, 0.3f}, 0.09f, rings, add_material(s, glm::vec3(0.7f)));
  finish(s);
  return s;
}

Image render_with(const Scene& s, const View& view, const VplSet& vpls, ShadowLodMode mode,
                  int batch = 16) {
  RasterOptions o;
  o.interleave = 1;
  o.batch = batch;
  o.shadow_lod.mode = mode;
  // The driver has nothing to say about any pass: its performance warnings (a page copied into a
  // buffer created for static use, one per copy) reach the user's terminal otherwise.
  std::vector<std::string> messages;
  o.gl_messages = [&](const std::string& m) { messages.push_back(m); };
  Image image = RasterRenderer(s, o).render(view, vpls);
  EXPECT_TRUE(messages.empty()) << messages.size() << " messages, the first: " << messages[0];
  return image;
}

TEST(ShadowLod, CullingChangesNoPixel) {
  Log log = quiet_log();
  const Scene s = cornell_with_sphere(100); // 39600 triangles
  const RayScene rays(s);
  const VplSet vpls = quasi_random_walk(s, rays, {16, 64}, log);
  const View view = make_view(s.cameras.at(0), s.bounds, 96, 96);
  const Image off = render_with(s, view, vpls, ShadowLodMode::Off);
  const Image cull = render_with(s, view, vpls, ShadowLodMode::Cull);
  maybe_write_side_by_side("shadow_cull", {&off, &cull});
  EXPECT_GT(mean_rgb(off), 0.0);
  EXPECT_TRUE(off.pixels() == cull.pixels()); // the same bits
}

// The level of detail against the full sphere, and both against exact visibility (rt-vpl).
// Measured (llvmpipe, 64^2 faces, texels 0.5): relMSE 1.05e-5 against the full meshes, mean
// ratio 1.00047; against rt-vpl 6.08e-4 with LOD, 6.00e-4 without. With a bug that draws empty
// inner meshes (the sphere gone from most faces): relMSE 1.2e-2, mean ratio 1.03.
TEST(ShadowLod, SimplifiedShadowsStayCloseToTheFullMeshes) {
  Log log = quiet_log();
  const Scene s = cornell_with_sphere(200); // 159200 triangles
  const RayScene rays(s);
  const VplSet vpls = quasi_random_walk(s, rays, {32, 64}, log);
  const View view = make_view(s.cameras.at(0), s.bounds, 128, 128);
  const Image off = render_with(s, view, vpls, ShadowLodMode::Off);
  const Image on = render_with(s, view, vpls, ShadowLodMode::On);
  const Image traced = trace_vpls(s, rays, view, vpls, {0.05f, 0});
  const Image error = relative_error_image(on, off, {0.02, 1});
  maybe_write_side_by_side("shadow_lod", {&off, &on, &error});
  const ImageMetrics lod = compare_images(on, off);
  const ImageMetrics full_vs_rt = compare_images(off, traced),
                     lod_vs_rt = compare_images(on, traced);
  std::printf("LOD against full shadows: relMSE %.3g, mean ratio %.5f; against rt-vpl: full "
              "%.3g, LOD %.3g\n",
              lod.relmse, lod.mean_ratio[1], full_vs_rt.relmse, lod_vs_rt.relmse);
  EXPECT_LT(lod.relmse, 3e-5);
  EXPECT_NEAR(lod.mean_ratio[1], 1.0, 1e-3);
  EXPECT_LT(lod_vs_rt.relmse, 1.1 * full_vs_rt.relmse);
}

// What the faces draw: triangles over a batch of the walk's VPLs in the atlas itself, with every
// triangle into every face (off), culled and with LOD. Measured (cornell + 159200-triangle
// sphere, 16 surface VPLs, 64^2 faces): off 16 x 6 x 159232 = 15.3M; culled 2.34M; LOD 33k (a
// face that sees the sphere from far draws one of its whole-sphere levels). The Cornell box split
// 4^7 times (524k): culled 8.6M, LOD 182k.
TEST(ShadowLod, TheFacesDrawFewerTrianglesWithLod) {
  Log log = quiet_log();
  const Scene s = cornell_with_sphere(200);
  const RayScene rays(s);
  const VplSet vpls = quasi_random_walk(s, rays, {16, 64}, log);
  std::vector<const Vpl*> batch;
  for (const Vpl& v : vpls.vpls)
    if (v.kind == VplKind::Surface && batch.size() < 16) batch.push_back(&v);
  ASSERT_EQ(batch.size(), 16u);
  const auto context = gl::create_osmesa_context();
  const gl::CurrentScope current(*context);
  const gl::GpuScene gpu(context->api(), s);
  std::vector<glm::mat3> frames;
  std::vector<float> fars;
  std::vector<glm::ivec4> blocks;
  std::size_t drawn[2] = {};
  for (int m = 0; m < 2; ++m) {
    const ShadowLodOptions lod{m == 0 ? ShadowLodMode::Cull : ShadowLodMode::On, 0.5f};
    gl::ShadowAtlas atlas(context->api(), 64, 16, 16, s.bounds, gpu.features(), lod);
    atlas.render(batch.data(), 16, gpu, frames, fars, blocks);
    drawn[m] = atlas.cluster_triangles();
  }
  const std::size_t all = 16 * 6 * s.triangle_count();
  std::printf("faces of 16 VPLs: %zu triangles drawn off, %zu culled, %zu with LOD\n", all,
              drawn[0], drawn[1]);
  EXPECT_LT(drawn[0], all);
  EXPECT_LT(drawn[1], drawn[0] / 40);
  EXPECT_GT(drawn[1], 0u);
}

// The GPU holds only the pages the faces draw, copied on first use into slabs: every node's
// mesh, original triangles and levels, picked in shuffled rounds, read back through select()'s
// ranges from the slabs, against the hierarchy's own indices; once from a build (indices in
// memory), once from a cache hit (indices in the file). Slabs of 8 pages, so that runs of pages
// cross slabs. After the first round (one leaf) the GPU holds one slab, not the hierarchy.
TEST(ShadowLod, PagesCopiedOnFirstUseDrawTheHierarchysIndices) {
  const Scene s = cornell_with_sphere(60); // 14k triangles, 58 pages
  const ClusterOptions options{128, true};
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("irad_lod_pages_" + std::to_string(::getpid()));
  std::filesystem::remove_all(folder);
  const auto context = gl::create_osmesa_context();
  const gl::CurrentScope current(*context);
  const GladGLContext& api = context->api();
  const gl::GpuScene gpu(api, s);
  for (int source = 0; source < 2; ++source) {
    CacheResult result;
    cached_mesh_clusters(s, options, folder, nullptr, &result); // written (or hit on round 2)
    MeshClusters clusters = source == 0
                                ? build_mesh_clusters(s, options)
                                : cached_mesh_clusters(s, options, folder, nullptr, &result);
    ASSERT_EQ(source == 1, clusters.stored_indices != nullptr);
    const std::vector<std::uint32_t> indices =
        source == 0 ? clusters.indices : clusters.stored_indices->read();
    std::vector<gl::ClusterPick> all;
    for (std::size_t n = 0; n < clusters.nodes.size(); ++n) {
      const ClusterNode& node = clusters.nodes[n];
      const auto id = static_cast<std::int32_t>(n);
      all.push_back({node.mesh_first, node.mesh_count, id});
      all.push_back({node.leaf_first, node.leaf_count, id});
      for (std::uint32_t l = 0; l < node.levels_count; ++l) {
        const ClusterLevel& level = clusters.levels[node.levels_first + l];
        all.push_back({level.first, level.count, id});
      }
    }
    std::shuffle(all.begin(), all.end(), std::mt19937(7));
    // A leaf first: the first round draws one page or two.
    const auto leaf = std::find_if(clusters.nodes.begin(), clusters.nodes.end(),
                                   [](const ClusterNode& n) { return n.leaf(); });
    ASSERT_NE(leaf, clusters.nodes.end());
    all.insert(all.begin(), {leaf->leaf_first, leaf->leaf_count, 0});
    const gl::ShadowLod lod(api, gpu, std::move(clusters), true, 8);
    const std::size_t pages =
        (indices.size() + gl::ShadowLod::kPageIndices - 1) / gl::ShadowLod::kPageIndices;
    ASSERT_GT(pages, 40u);
    EXPECT_EQ(lod.gpu_bytes(), 0u);
    gl::ClusterSelection selection;
    const std::size_t rounds[] = {1, 5, 40, all.size()};
    std::size_t begin = 0;
    for (std::size_t end : rounds) {
      end = std::min(end, all.size());
      std::vector<gl::ClusterPick> round(all.begin() + static_cast<std::ptrdiff_t>(begin),
                                         all.begin() + static_cast<std::ptrdiff_t>(end));
      std::sort(round.begin(), round.end(),
                [](const auto& a, const auto& b) { return a.first < b.first; });
      lod.make_resident({round});
      lod.select(round, selection);
      std::vector<std::uint32_t> drawn, wanted;
      std::size_t triangles = 0;
      for (const gl::ClusterPick& p : round) {
        wanted.insert(wanted.end(), indices.begin() + p.first, indices.begin() + p.first + p.count);
        triangles += p.count / 3;
      }
      drawn = test_support::selected_indices(api, selection);
      // Slab by slab, the ranges of one slab in pick order: the same multiset of triangles.
      const auto triangles_of = test_support::triangle_set;
      EXPECT_EQ(selection.triangles, triangles);
      EXPECT_EQ(drawn.size(), wanted.size()) << "round to " << end;
      EXPECT_TRUE(triangles_of(drawn) == triangles_of(wanted)) << "round to " << end;
      if (begin == 0) {
        EXPECT_EQ(lod.gpu_bytes(), 8 * gl::ShadowLod::kPageIndices * 4);
      }
      begin = end;
    }
    // Every pick made resident: all pages, in slabs of 8 (the last one holds what is left).
    EXPECT_EQ(lod.gpu_bytes(), pages * gl::ShadowLod::kPageIndices * 4);
  }
  std::filesystem::remove_all(folder);
}

// ---------------------------------------------------------------------------------------------
// No new light leaks: tests/test_two_rooms.cpp's two rooms (a 2 mm wall between them, every VPL
// in room A) with every quad split 4^5 times, so that the shadow faces draw simplified walls
// (each room is one closed box: its root mesh is 12 triangles at error 0).

using test_support::add_room;

struct Lit {
  std::size_t pixels = 0;
  double max = 0.0;
};
Lit lit(const Image& image) {
  Lit l;
  for (const glm::vec4& p : image.pixels()) {
    const double v = std::max({p.r, p.g, p.b});
    if (v == 0.0) continue;
    ++l.pixels;
    l.max = std::max(l.max, v);
  }
  return l;
}

TEST(ShadowLod, NoNewLeaksBetweenTwoSubdividedRooms) {
  Log log = quiet_log();
  Scene s;
  const std::uint32_t wall = add_material(s, glm::vec3(0.6f));
  const std::uint32_t light = add_material(s, glm::vec3(0.6f), glm::vec3(5.0f));
  add_room(s, {0.0f, 0.0f, 0.0f}, {2.0f, 2.0f, 2.0f}, wall);
  add_room(s, {2.002f, 0.0f, 0.0f}, {4.002f, 2.0f, 2.0f}, wall);
  add_quad(s, {0.7f, 1.999f, 0.7f}, {1.3f, 1.999f, 0.7f}, {1.3f, 1.999f, 1.3f},
           {0.7f, 1.999f, 1.3f}, light);
  subdivide(s, 4); // 6656 triangles
  finish(s);
  const RayScene rays(s);
  const VplSet vpls = quasi_random_walk(s, rays, {128, 64}, log);
  const View in_b = make_view(look_at({3.95f, 1.05f, 1.03f}, {2.002f, 0.9f, 1.0f}, {0, 1, 0}, 1.5f),
                              s.bounds, 64, 64);
  const View in_a = make_view(look_at({0.05f, 1.05f, 1.03f}, {2.0f, 0.9f, 1.0f}, {0, 1, 0}, 1.5f),
                              s.bounds, 64, 64);
  for (int k : {1, 4}) {
    RasterOptions o;
    o.shadow_resolution = 256;
    o.interleave = k;
    o.shadow_lod.mode = ShadowLodMode::Off;
    RasterRenderer full(s, o);
    o.shadow_lod.mode = ShadowLodMode::On;
    RasterRenderer lod(s, o);
    const Lit a = lit(full.render(in_b, vpls)), b = lit(lod.render(in_b, vpls));
    const ImageMetrics room_a = compare_images(lod.render(in_a, vpls), full.render(in_a, vpls));
    std::printf("two subdivided rooms, k = %d: room B lit pixels %zu (max %.3g) full, %zu (max "
                "%.3g) LOD; room A LOD against full: relMSE %.3g, mean ratio %.5f\n",
                k, a.pixels, a.max, b.pixels, b.max, room_a.relmse, room_a.mean_ratio[1]);
    // Measured: 5 (k = 1) and 28 (k = 4) lit pixels in room B
    // with and without LOD, the same values; room A relMSE 0 (the walls simplify at error 0).
    EXPECT_LE(b.pixels, a.pixels) << k;
    EXPECT_LE(b.max, a.max * 1.001 + 1e-6) << k;
    EXPECT_LT(room_a.relmse, 1e-4) << k;
  }
}

} // namespace IRAD_UNITY_ID
} // namespace irad
