// Coarser levels built when a shadow face first needs them (ClusterOptions::defer_levels,
// core/mesh/hierarchy/cluster_levels.h add_deferred_levels, raster/shadow/shadow_lod.h): the very
// levels a build makes with the hierarchy, the very cuts the faces pick then, their pages on the
// GPU as the indices say, the same image, and the levels kept beside the hierarchy's cache file
// for the next render, where a damaged file is never trusted.
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/mesh/hierarchy/cluster_cache.h"
#include "core/mesh/hierarchy/cluster_levels.h"
#include "core/mesh/hierarchy/mesh_clusters.h"
#include "core/mesh/local_vertices.h"
#include "core/mesh/sphere_mesh.h"
#include "core/scene/scene_builder.h"
#include "raster/context/gl_context.h"
#include "raster/raster_renderer.h"
#include "raster/scene/gpu_scene.h"
#include "raster/shadow/shadow_lod.h"
#include "tests/shadow_lod_support.h"
#include "tests/test_paths.h"
#include "walk/vpls/quasi_random_walk.h"

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <random>
#include <unistd.h>

namespace irad {
namespace IRAD_UNITY_ID {

namespace fs = std::filesystem;

// Spheres of several sizes (components with levels of their own) and small ones (the tree of
// the rest), leaves of 128 triangles (leaves keep levels too).
Scene spheres() {
  Scene s;
  add_sphere(s, {0.0f, 0.0f, 0.0f}, 2.0f, 64, add_material(s, glm::vec3(0.5f)));
  add_sphere(s, {5.0f, 0.0f, 0.0f}, 1.0f, 32, add_material(s, glm::vec3(0.5f)));
  for (int k = 0; k < 12; ++k)
    add_sphere(s, glm::vec3(float(k), -4.0f, 0.0f), 0.3f, 4, add_material(s, glm::vec3(0.5f)));
  finish(s);
  return s;
}

ClusterOptions options(bool defer) {
  ClusterOptions o{128, true};
  o.defer_levels = defer;
  return o;
}

// Indices [first, first + count) of c's index space (its own, stored, or late).
std::vector<std::uint32_t> range_of(const MeshClusters& c, std::size_t first, std::size_t count) {
  if (first >= c.late_base() && !c.late_indices.empty()) {
    const auto at = c.late_indices.begin() + static_cast<std::ptrdiff_t>(first - c.late_base());
    return {at, at + static_cast<std::ptrdiff_t>(count)};
  }
  std::vector<std::uint32_t> out(count);
  if (c.stored_indices)
    c.stored_indices->copy_range(first, count, out.data());
  else
    std::copy_n(c.indices.begin() + static_cast<std::ptrdiff_t>(first), count, out.begin());
  return out;
}

// Node n's levels in a and b: the same errors and the same triangles, in the same order.
bool same_levels(const MeshClusters& a, const MeshClusters& b, std::size_t n) {
  const ClusterNode &x = a.nodes[n], &y = b.nodes[n];
  if (x.levels_pending() || y.levels_pending() || x.levels_count != y.levels_count) return false;
  for (std::uint32_t l = 0; l < x.levels_count; ++l) {
    const ClusterLevel &p = a.levels[x.levels_first + l], &q = b.levels[y.levels_first + l];
    if (p.error != q.error || p.count != q.count ||
        range_of(a, p.first, p.count) != range_of(b, q.first, q.count))
      return false;
  }
  return true;
}

TEST(DeferredLevels, LocalNumbersAsThroughAMap) {
  std::mt19937 random(3);
  std::vector<std::uint32_t> map(5000, kNoLocal);
  for (std::size_t n : {0, 1, 7, 300, 3000}) {
    std::vector<std::uint32_t> part(n);
    for (std::uint32_t& v : part) v = static_cast<std::uint32_t>(random() % 5000);
    const LocalVertices hashed = local_vertices(part), mapped = local_vertices(part, map);
    EXPECT_EQ(hashed.local, mapped.local) << n;
    EXPECT_EQ(hashed.global, mapped.global) << n;
  }
}

// The nodes whose levels are pending in c.
std::vector<std::int32_t> pending_nodes(const MeshClusters& c) {
  std::vector<std::int32_t> out;
  for (std::size_t n = 0; n < c.nodes.size(); ++n)
    if (c.nodes[n].levels_pending()) out.push_back(static_cast<std::int32_t>(n));
  return out;
}

// On one thread the build gives the roots of components their levels and leaves every other
// node's pending; on more, some of those are built beside the roots' (which, depends on the
// timing). Built later, in two calls of shuffled nodes, from indices in memory and from a cache
// file: the levels the build gives every node with the hierarchy.
TEST(DeferredLevels, TheLevelsTheBuildGives) {
  const Scene s = spheres();
  const MeshClusters eager = build_mesh_clusters(s, options(false));
  ClusterOptions one = options(true);
  one.threads = 1;
  MeshClusters serial = build_mesh_clusters(s, one);
  std::size_t candidates = 0; // nodes with levels, other than the two spheres' roots
  for (std::size_t n = 0; n < eager.nodes.size(); ++n)
    candidates += eager.nodes[n].levels_count > 0 ? 1 : 0;
  EXPECT_EQ(pending_nodes(serial).size() + 2, candidates);
  std::size_t roots_built = 0; // the two spheres' (the small ones' tree waits too)
  for (std::int32_t root : serial.roots)
    roots_built += serial.nodes[static_cast<std::size_t>(root)].levels_pending() ? 0 : 1;
  EXPECT_EQ(roots_built, 2u);
  MeshClusters beside = build_mesh_clusters(s, options(true));
  const fs::path folder =
      fs::temp_directory_path() / ("irad_deferred_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  CacheResult result;
  cached_mesh_clusters(s, options(true), folder, nullptr, &result);
  MeshClusters stored = cached_mesh_clusters(s, options(true), folder, nullptr, &result);
  ASSERT_EQ(result.outcome, CacheOutcome::Hit);
  ASSERT_TRUE(stored.stored_indices);
  for (MeshClusters* c : {&serial, &beside, &stored}) {
    std::vector<std::int32_t> pending = pending_nodes(*c);
    std::shuffle(pending.begin(), pending.end(), std::mt19937(5));
    const std::size_t half = pending.size() / 2;
    add_deferred_levels(s, *c, {pending.begin(), pending.begin() + half}, 2);
    EXPECT_EQ(c->late_nodes.size(), half);
    EXPECT_EQ(c->late_base() % kLateAlign, 0u);
    add_deferred_levels(s, *c, {pending.begin(), pending.end()}, 3); // the first half again
    EXPECT_EQ(c->late_nodes.size(), pending.size());
    EXPECT_TRUE(pending_nodes(*c).empty());
    EXPECT_EQ(validate_clusters(*c, s.positions.size(), s.triangle_count(), s.materials.size()),
              "");
  }
  for (std::size_t n = 0; n < eager.nodes.size(); ++n) {
    EXPECT_TRUE(same_levels(eager, serial, n)) << "node " << n;
    EXPECT_TRUE(same_levels(eager, beside, n)) << "node " << n << ", beside the roots";
    EXPECT_TRUE(same_levels(eager, stored, n)) << "node " << n << ", stored";
  }
  fs::remove_all(folder);
}

// A cube face's view-projection from `origin` along axis `face` (90 degrees, as the shadow
// cubes draw).
glm::mat4 cube_face(const glm::vec3& origin, int face) {
  static const glm::vec3 axes[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                    {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  const glm::vec3 d = axes[face],
                  up = std::abs(d.y) > 0.5f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
  return glm::perspective(glm::radians(90.0f), 1.0f, 0.01f, 100.0f) *
         glm::lookAt(origin, origin + d, up);
}

// What a face draws: per pick, its node and its triangles.
using Cut = std::vector<std::pair<std::int32_t, std::vector<std::uint32_t>>>;

// The faces of VPLs near and far, at several resolutions, picked from `lod` as the atlas picks
// (deferred levels built round by round), each face's pages made resident after its pick;
// `rounds` gets the rounds that built levels.
std::vector<Cut> cuts(const gl::ShadowLod& lod, int& rounds) {
  std::mt19937 random(11);
  std::uniform_real_distribution<float> u(-9.0f, 9.0f);
  gl::ShadowLod::Plans plans;
  std::vector<Cut> out;
  rounds = 0;
  for (int v = 0; v < 24; ++v) {
    const glm::vec3 origin(u(random), u(random), u(random) * (v % 2 == 0 ? 0.2f : 3.0f));
    const int resolution = 16 << (v % 3) * 2; // 16, 64, 256 texels
    for (int f = 0; f < 6; ++f) {
      const auto planes = gl::face_planes(cube_face(origin, f),
                                          glm::vec4(0, 0, resolution, resolution), resolution);
      std::vector<gl::ClusterPick> picks;
      for (std::vector<std::int32_t> wanted{-1}; !wanted.empty();) {
        wanted.clear();
        picks.clear();
        lod.pick(planes, origin, 1.0f / float(resolution), 1e-6f, plans, picks, &wanted);
        if (!wanted.empty()) {
          lod.build_levels(wanted);
          ++rounds;
        }
      }
      Cut cut;
      for (const gl::ClusterPick& p : picks)
        cut.emplace_back(p.node, range_of(lod.clusters(), p.first, p.count));
      out.push_back(std::move(cut));
      lod.make_resident({picks}); // slabs made while the late pages still grow
    }
  }
  return out;
}

// The triangles the GPU holds for `picks` (made resident), through select()'s ranges.
std::vector<std::uint32_t> drawn(const GladGLContext& api, const gl::ShadowLod& lod,
                                 const std::vector<gl::ClusterPick>& picks) {
  lod.make_resident({picks});
  gl::ClusterSelection selection;
  lod.select(picks, selection);
  return test_support::selected_indices(api, selection);
}

// The faces pick the cuts they pick with every level built beforehand, node by node and
// triangle by triangle, having built a part of the levels; the late pages reach the GPU as the
// late indices hold them (slabs of 8 pages, made as the pages grow).
TEST(DeferredLevels, TheFacesPickTheCutsOfEveryLevelBuilt) {
  const Scene s = spheres();
  const auto context = gl::create_osmesa_context();
  const gl::CurrentScope current(*context);
  const GladGLContext& api = context->api();
  const gl::GpuScene gpu(api, s);
  const gl::ShadowLod eager(api, gpu, build_mesh_clusters(s, options(false)), true, 8);
  ClusterOptions one = options(true); // every level but the roots' pending
  one.threads = 1;
  const gl::ShadowLod deferred(api, gpu, build_mesh_clusters(s, one), true, 8);
  // Every page of the hierarchy's own indices on the GPU first: its last slab holds what is left
  // (fewer than 8 pages), and the late pages must start a slab of their own.
  const MeshClusters& built = deferred.clusters();
  std::vector<gl::ClusterPick> base;
  for (std::size_t n = 0; n < built.nodes.size(); ++n) {
    const ClusterNode& node = built.nodes[n];
    base.push_back({node.mesh_first, node.mesh_count, static_cast<std::int32_t>(n)});
    base.push_back({node.leaf_first, node.leaf_count, static_cast<std::int32_t>(n)});
    for (std::uint32_t l = 0; l < node.levels_count; ++l) // the roots'
      base.push_back({built.levels[node.levels_first + l].first,
                      built.levels[node.levels_first + l].count, static_cast<std::int32_t>(n)});
  }
  deferred.make_resident({base});
  const std::size_t pages =
      (built.index_count() + gl::ShadowLod::kPageIndices - 1) / gl::ShadowLod::kPageIndices;
  ASSERT_NE(pages % 8, 0u);
  int rounds = 0;
  const std::vector<Cut> want = cuts(eager, rounds);
  EXPECT_EQ(rounds, 0);
  const std::vector<Cut> got = cuts(deferred, rounds);
  EXPECT_GT(rounds, 6);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t f = 0; f < want.size(); ++f) EXPECT_TRUE(got[f] == want[f]) << "face " << f;
  const MeshClusters& c = deferred.clusters();
  std::size_t pending = 0;
  for (const ClusterNode& n : c.nodes) pending += n.levels_pending() ? 1 : 0;
  std::printf("deferred levels: %zu of %zu nodes built in %d rounds, %zu still pending\n",
              deferred.late_levels().nodes, c.nodes.size(), rounds, pending);
  EXPECT_EQ(deferred.late_levels().nodes, c.late_nodes.size());
  EXPECT_GT(pending, 0u); // some never wanted
  // Every late level, and a base mesh beside it, drawn from the slabs.
  std::vector<gl::ClusterPick> picks;
  std::vector<std::uint32_t> expected;
  for (std::int32_t n : c.late_nodes) {
    const ClusterNode& node = c.nodes[static_cast<std::size_t>(n)];
    for (std::uint32_t l = 0; l < node.levels_count; ++l) {
      const ClusterLevel& level = c.levels[node.levels_first + l];
      picks.push_back({level.first, level.count, n});
    }
    picks.push_back({node.mesh_first, node.mesh_count, n});
  }
  for (const gl::ClusterPick& p : picks) {
    const std::vector<std::uint32_t> r = range_of(c, p.first, p.count);
    expected.insert(expected.end(), r.begin(), r.end());
  }
  const auto triangles = test_support::triangle_set;
  const std::vector<std::uint32_t> from_gpu = drawn(api, deferred, picks);
  EXPECT_EQ(from_gpu.size(), expected.size());
  EXPECT_TRUE(triangles(from_gpu) == triangles(expected));
}

// ---------------------------------------------------------------------------------------------
// The raster: the same image as with every level built, and the levels kept for the next render.

using test_support::SphereBox;

class DeferredLevelsCache : public ::testing::Test {
protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("irad_late_levels_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  // A render through the cache (or none: `cache` false), on demand or not.
  Image render(const SphereBox& b, bool on_demand, bool cache, RasterTimings* timings) {
    RasterOptions o;
    o.interleave = 1;
    o.shadow_lod.levels_on_demand = on_demand;
    o.hierarchy_cache = cache ? folder_ : fs::path();
    return RasterRenderer(b.s, o).render(b.view, b.vpls, timings);
  }
  // The late levels' file the folder holds.
  fs::path late_file() const {
    for (const fs::directory_entry& e : fs::directory_iterator(folder_))
      if (e.path().extension() == ".lvl") return e.path();
    return {};
  }
  fs::path folder_;
};

TEST_F(DeferredLevelsCache, TheImageOfEveryLevelBuiltAndTheLevelsKept) {
  const SphereBox b = test_support::sphere_box(100);
  RasterTimings t;
  const Image all = render(b, false, false, &t);
  EXPECT_EQ(t.shadow_levels_built, 0u);
  const Image cold = render(b, true, true, &t);
  EXPECT_GT(t.shadow_levels_built, 0u);
  EXPECT_EQ(t.shadow_levels_read, 0u);
  const std::size_t built = t.shadow_levels_built;
  EXPECT_TRUE(cold.pixels() == all.pixels()); // the same bits
  const fs::path late = late_file();
  ASSERT_FALSE(late.empty());
  // Warm: the levels read back, none built, the same image.
  const Image warm = render(b, true, true, &t);
  EXPECT_EQ(t.shadow_levels_read, built);
  EXPECT_EQ(t.shadow_levels_built, 0u);
  EXPECT_TRUE(warm.pixels() == all.pixels());
  // A damaged late file: ignored, the levels built again, the image the same, the file written
  // over with what was built.
  const std::uintmax_t size = fs::file_size(late);
  std::vector<char> good(size);
  std::ifstream(late, std::ios::binary).read(good.data(), static_cast<std::streamsize>(size));
  const auto write = [&](const std::vector<char>& bytes) {
    std::ofstream(late, std::ios::binary | std::ios::trunc)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  };
  std::vector<std::vector<char>> bad;
  for (std::uintmax_t cut : {std::uintmax_t{0}, std::uintmax_t{30}, size / 2, size - 1})
    bad.emplace_back(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(cut));
  for (std::uintmax_t at : {std::uintmax_t{5}, std::uintmax_t{12}, std::uintmax_t{40},
                            std::uintmax_t{70}, size / 3, size - 20, size - 2}) {
    bad.push_back(good);
    bad.back()[at] = static_cast<char>(bad.back()[at] ^ 0x08);
  }
  for (std::size_t k = 0; k < bad.size(); ++k) {
    write(bad[k]);
    const Image again = render(b, true, true, &t);
    EXPECT_EQ(t.shadow_levels_read, 0u) << "damage " << k;
    EXPECT_EQ(t.shadow_levels_built, built) << "damage " << k;
    EXPECT_TRUE(again.pixels() == all.pixels()) << "damage " << k;
    EXPECT_EQ(fs::file_size(late), size) << "damage " << k << ": written over";
  }
}

} // namespace IRAD_UNITY_ID
} // namespace irad
