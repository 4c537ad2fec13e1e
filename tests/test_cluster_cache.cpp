// The shadow hierarchy's cache (core/mesh/hierarchy/cluster_cache.h): a hit gives the hierarchy the
// build gives; a file that is truncated, bit-flipped, of another scene or another version is never
// used but rebuilt and written over; a folder that cannot be written costs only the write; the
// renderer draws the same image from a hit as from a build, and from a build on a thread of its own
// (core/mesh/hierarchy/background_clusters.h) as from one in place.
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/mesh/hierarchy/background_clusters.h"
#include "core/mesh/hierarchy/cluster_cache.h"
#include "core/mesh/sphere_mesh.h"
#include "core/scene/scene_builder.h"
#include "core/util/error.h"
#include "raster/raster_renderer.h"
#include "tests/shadow_lod_support.h"
#include "tests/test_paths.h"
#include "walk/vpls/quasi_random_walk.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <limits>
#include <string>
#include <unistd.h>
#include <vector>

namespace irad {
namespace IRAD_UNITY_ID {

namespace fs = std::filesystem;

Scene two_spheres() {
  Scene s;
  add_sphere(s, {0.0f, 0.0f, 0.0f}, 1.0f, 32, add_material(s, glm::vec3(0.5f)));
  add_sphere(s, {3.0f, 0.0f, 0.0f}, 0.5f, 16, add_material(s, glm::vec3(0.5f)));
  finish(s);
  return s;
}

// The indices, from memory or from the cache file.
std::vector<std::uint32_t> indices_of(const MeshClusters& c) {
  return c.stored_indices ? c.stored_indices->read() : c.indices;
}

bool same(const MeshClusters& a, const MeshClusters& b) {
  if (indices_of(a) != indices_of(b) || a.roots != b.roots || a.triangles != b.triangles ||
      a.original_indices != b.original_indices || a.nodes.size() != b.nodes.size() ||
      a.levels.size() != b.levels.size())
    return false;
  for (std::size_t k = 0; k < a.nodes.size(); ++k) {
    const ClusterNode &x = a.nodes[k], &y = b.nodes[k];
    if (x.error != y.error || x.mesh_first != y.mesh_first || x.mesh_count != y.mesh_count ||
        x.leaf_first != y.leaf_first || x.leaf_count != y.leaf_count ||
        x.children[0] != y.children[0] || x.children[1] != y.children[1] ||
        x.levels_first != y.levels_first || x.levels_count != y.levels_count ||
        x.bounds.lo != y.bounds.lo || x.bounds.hi != y.bounds.hi)
      return false;
  }
  for (std::size_t k = 0; k < a.levels.size(); ++k)
    if (a.levels[k].error != b.levels[k].error || a.levels[k].first != b.levels[k].first ||
        a.levels[k].count != b.levels[k].count)
      return false;
  return true;
}

class ClusterCache : public ::testing::Test {
protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("irad_cluster_cache_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  // The one file the folder holds.
  fs::path file() const {
    std::vector<fs::path> files;
    for (const fs::directory_entry& e : fs::directory_iterator(folder_)) files.push_back(e.path());
    EXPECT_EQ(files.size(), 1u);
    return files.empty() ? fs::path() : files[0];
  }
  MeshClusters cached(const Scene& s, CacheResult& result, StageTimes* times = nullptr) const {
    return cached_mesh_clusters(s, options_, folder_, times, &result);
  }

  fs::path folder_;
  ClusterOptions options_{128, true};
};

TEST_F(ClusterCache, AHitGivesWhatTheBuildGives) {
  const Scene s = two_spheres();
  const MeshClusters built = build_mesh_clusters(s, options_);
  CacheResult result;
  const MeshClusters written = cached(s, result);
  EXPECT_TRUE(same(written, built));
  EXPECT_EQ(result.outcome, CacheOutcome::Written);
  // Written, its indices are left in the file as a hit's are (none held in memory).
  EXPECT_TRUE(written.stored_indices && written.indices.empty());
  EXPECT_EQ(file().filename().string(), cluster_key(s, options_).hex() + ".lod");
  StageTimes times;
  EXPECT_TRUE(same(cached(s, result, &times), built));
  EXPECT_EQ(result.outcome, CacheOutcome::Hit);
  ASSERT_EQ(times.stages().size(), 1u);
  EXPECT_EQ(times.stages()[0].first, "cache read");
  // Off: built, nothing written, the indices in memory.
  fs::remove_all(folder_);
  const MeshClusters off = cached_mesh_clusters(s, options_, {}, nullptr, &result);
  EXPECT_TRUE(same(off, built));
  EXPECT_TRUE(!off.stored_indices && !off.indices.empty());
  EXPECT_EQ(result.outcome, CacheOutcome::Off);
  EXPECT_FALSE(fs::exists(folder_));
}

TEST_F(ClusterCache, TheKeyFollowsWhatTheBuildReads) {
  const Scene s = two_spheres();
  const ClusterKey key = cluster_key(s, options_);
  EXPECT_EQ(key, cluster_key(two_spheres(), options_));
  ClusterOptions threads = options_;
  threads.threads = 1; // the same hierarchy on any number
  EXPECT_EQ(key, cluster_key(s, threads));
  ClusterOptions leaves = options_;
  leaves.leaf_triangles = 256;
  EXPECT_NE(key, cluster_key(s, leaves));
  ClusterOptions cull = options_;
  cull.simplify = false;
  EXPECT_NE(key, cluster_key(s, cull));
  Scene moved = two_spheres();
  moved.positions[7].y += 1e-6f;
  EXPECT_NE(key, cluster_key(moved, options_));
  Scene masked = two_spheres();
  masked.materials[1].alpha_mode = AlphaMode::Mask; // out of the hierarchy
  EXPECT_NE(key, cluster_key(masked, options_));
}

// A truncated file, a flipped bit anywhere (header, indices, nodes, checksum), a file of another
// scene under this one's name: each is rebuilt, written over, and the result is the build's.
TEST_F(ClusterCache, ABadFileIsRebuiltNeverTrusted) {
  const Scene s = two_spheres();
  const MeshClusters built = build_mesh_clusters(s, options_);
  CacheResult result;
  cached(s, result);
  const fs::path path = file();
  const std::uintmax_t size = fs::file_size(path);
  std::vector<char> good(size);
  std::ifstream(path, std::ios::binary).read(good.data(), static_cast<std::streamsize>(size));
  const auto write = [&](const std::vector<char>& bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  };
  const auto expect_rebuilt = [&](const std::string& what) {
    const MeshClusters c = cached(s, result);
    EXPECT_EQ(result.outcome, CacheOutcome::Rebuilt) << what;
    EXPECT_FALSE(result.reason.empty()) << what;
    EXPECT_TRUE(same(c, built)) << what;
    EXPECT_EQ(fs::file_size(path), size) << what << ": written over";
  };
  for (std::uintmax_t cut : {std::uintmax_t{0}, std::uintmax_t{40}, size / 2, size - 1}) {
    write(std::vector<char>(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(cut)));
    expect_rebuilt("truncated to " + std::to_string(cut));
  }
  for (std::uintmax_t at :
       {std::uintmax_t{3}, std::uintmax_t{10}, std::uintmax_t{20}, std::uintmax_t{40},
        std::uintmax_t{100}, size / 3, size / 2, size - 12, size - 1}) {
    std::vector<char> flipped = good;
    flipped[at] = static_cast<char>(flipped[at] ^ 0x10);
    write(flipped);
    expect_rebuilt("bit flipped at byte " + std::to_string(at));
  }
  // Another scene's file under this name: its key differs.
  Scene other = two_spheres();
  other.positions[0].x += 0.25f;
  fs::remove_all(folder_);
  cached(other, result);
  fs::rename(file(), path);
  expect_rebuilt("another scene's file");
  // Extra bytes after the checksum.
  std::vector<char> padded = good;
  padded.push_back(0);
  write(padded);
  expect_rebuilt("padded");
  // And the good file again: a hit.
  write(good);
  EXPECT_TRUE(same(cached(s, result), built));
  EXPECT_EQ(result.outcome, CacheOutcome::Hit);
}

// A hit keeps its indices in the file until they are copied: a file renamed over it or removed
// leaves the copy as checked; a change in place is caught by the copy, which names the file.
TEST_F(ClusterCache, AHitReadsItsIndicesFromTheFileItChecked) {
  const Scene s = two_spheres();
  const MeshClusters built = build_mesh_clusters(s, options_);
  CacheResult result;
  cached(s, result);
  const fs::path path = file();
  const MeshClusters hit = cached(s, result);
  ASSERT_EQ(result.outcome, CacheOutcome::Hit);
  ASSERT_TRUE(hit.stored_indices);
  EXPECT_TRUE(hit.indices.empty());
  EXPECT_EQ(hit.index_count(), built.indices.size());
  // Another file renamed into its place, then removed: the hit still reads what it checked.
  const fs::path other = folder_ / "other";
  std::ofstream(other, std::ios::binary) << "not a hierarchy";
  fs::rename(other, path);
  fs::remove(path);
  EXPECT_EQ(hit.stored_indices->read(), built.indices);

  // Written over in place after the check (not irad's way of writing): an index past the
  // vertices, then a file cut short.
  cached(s, result);
  const MeshClusters changed = cached(s, result);
  ASSERT_EQ(result.outcome, CacheOutcome::Hit);
  {
    std::fstream f(path, std::ios::binary | std::ios::in | std::ios::out);
    const std::uint32_t past = 0xffffffffu;
    f.seekp(96 + 4 * 7); // the 8th index, after the 96-byte header
    f.write(reinterpret_cast<const char*>(&past), sizeof past);
  }
  try {
    changed.stored_indices->read();
    ADD_FAILURE() << "a changed index was copied";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  // A part (what the shadow passes copy page by page) is checked alike: the range with the
  // changed index throws, the one before it reads as built; a range past the end throws.
  std::uint32_t part[4] = {};
  EXPECT_THROW(changed.stored_indices->copy_range(5, 4, part), Error);
  changed.stored_indices->copy_range(3, 4, part);
  EXPECT_TRUE(std::equal(part, part + 4, built.indices.begin() + 3));
  EXPECT_THROW(changed.stored_indices->copy_range(changed.index_count() - 2, 4, part), Error);
  fs::resize_file(path, 100);
  EXPECT_THROW(changed.stored_indices->read(), Error);
}

TEST_F(ClusterCache, AFolderThatCannotBeWrittenCostsOnlyTheWrite) {
  const Scene s = two_spheres();
  std::ofstream(folder_.string()) << "a file where the folder should be";
  CacheResult result;
  const MeshClusters c = cached_mesh_clusters(s, options_, folder_ / "sub", nullptr, &result);
  EXPECT_EQ(result.outcome, CacheOutcome::Unwritable);
  EXPECT_NE(result.reason.find("cannot write"), std::string::npos) << result.reason;
  EXPECT_TRUE(same(c, build_mesh_clusters(s, options_)));
  fs::remove(folder_);
}

TEST(ClusterCacheValidation, NamesWhatIsWrong) {
  const Scene s = two_spheres();
  const MeshClusters good = build_mesh_clusters(s, ClusterOptions{128, true});
  const std::size_t vertices = s.positions.size(), triangles = s.triangle_count();
  EXPECT_EQ(validate_clusters(good, vertices, triangles, 1000), "");
  MeshClusters c = good;
  c.indices[5] = static_cast<std::uint32_t>(vertices);
  EXPECT_NE(validate_clusters(c, vertices, triangles, 1000), "");
  c = good;
  c.nodes[0].children[1] = 0; // a cycle
  EXPECT_NE(validate_clusters(c, vertices, triangles, 1000), "");
  c = good;
  c.nodes.back().levels_first = static_cast<std::uint32_t>(c.levels.size());
  c.nodes.back().levels_count = 1;
  EXPECT_NE(validate_clusters(c, vertices, triangles, 1000), "");
  c = good;
  c.levels[0].count = static_cast<std::uint32_t>(c.indices.size()) + 3;
  EXPECT_NE(validate_clusters(c, vertices, triangles, 1000), "");
  c = good;
  c.triangles = {0, static_cast<std::uint32_t>(triangles)}; // (a list: some left out)
  EXPECT_NE(validate_clusters(c, vertices, triangles, 1000), "");
  c = good;
  c.nodes[1].error = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(validate_clusters(c, vertices, triangles, 1000), "");
}

// The raster through the cache: the image from a hit is the image from the build, bit for bit.
// The Cornell box with a sphere of 9800 triangles, which the faces draw simplified; its VPLs and
// a 64x64 view.
test_support::SphereBox sphere_box() {
  return test_support::sphere_box(50);
}

TEST_F(ClusterCache, TheRasterDrawsTheSameImageFromAHit) {
  const auto [s, vpls, view] = sphere_box();
  RasterOptions o;
  o.interleave = 1;
  o.hierarchy_cache = folder_;
  RasterRenderer first(s, o);
  const Image built = first.render(view, vpls);
  EXPECT_EQ(first.hierarchy_cache().outcome, CacheOutcome::Written);
  RasterRenderer second(s, o);
  const Image hit = second.render(view, vpls);
  EXPECT_EQ(second.hierarchy_cache().outcome, CacheOutcome::Hit);
  EXPECT_TRUE(built.pixels() == hit.pixels());
}

// Built on a thread of its own: the hierarchy of a build in place, through the same cache; taken
// once; a renderer given it draws the image of one that builds its own, and one given a build of
// other options builds what it needs itself.
TEST_F(ClusterCache, ABuildBesideGivesWhatTheBuildGives) {
  const Scene s = two_spheres();
  const MeshClusters built = build_mesh_clusters(s, options_);
  BackgroundClusters beside(s, options_, folder_);
  EXPECT_TRUE(beside.builds(s, options_, folder_));
  EXPECT_FALSE(beside.builds(s, {128, false}, folder_));
  EXPECT_FALSE(beside.builds(s, options_, {}));
  const MeshClusters taken = beside.take();
  EXPECT_TRUE(same(taken, built));
  // Handed on before its file is written: the indices shared with the writer, in memory until
  // the file is written, then read from it.
  ASSERT_TRUE(taken.stored_indices && taken.indices.empty());
  EXPECT_FALSE(beside.builds(s, options_, folder_));               // taken
  EXPECT_EQ(beside.cache_result().outcome, CacheOutcome::Written); // waits for the write
  EXPECT_EQ(beside.times().stages().back().first, "cache write");
  EXPECT_EQ(taken.stored_indices->in_memory(), nullptr);
  EXPECT_TRUE(same(taken, built));
  EXPECT_EQ(file().filename().string(), cluster_key(s, options_).hex() + ".lod");
  BackgroundClusters again(s, options_, folder_);
  const MeshClusters hit = again.take();
  EXPECT_TRUE(same(hit, built));
  EXPECT_EQ(again.cache_result().outcome, CacheOutcome::Hit);
  ASSERT_TRUE(hit.stored_indices);
  EXPECT_EQ(hit.stored_indices->in_memory(), nullptr); // in the file
  // What the first one handed on still reads the same after its writer let go.
  EXPECT_TRUE(same(taken, built));
}

// wait_for_build: after a build it returns once the file is written (the indices then read from
// it, their memory gone); after a hit it returns too, and the hit gives the same hierarchy.
TEST_F(ClusterCache, WaitForBuildEndsWithTheWrite) {
  const Scene s = two_spheres();
  BackgroundClusters built(s, options_, folder_);
  built.wait_for_build();
  EXPECT_EQ(file().filename().string(), cluster_key(s, options_).hex() + ".lod");
  const MeshClusters taken = built.take();
  EXPECT_EQ(taken.stored_indices->in_memory(), nullptr);
  EXPECT_EQ(built.cache_result().outcome, CacheOutcome::Written);
  BackgroundClusters hit(s, options_, folder_);
  hit.wait_for_build();
  EXPECT_TRUE(same(hit.take(), taken));
  EXPECT_EQ(hit.cache_result().outcome, CacheOutcome::Hit);
  // A write that fails (the cache folder is a file) lets the waiter go too; the indices stay in
  // memory.
  fs::remove_all(folder_);
  fs::create_directories(folder_.parent_path());
  std::ofstream(folder_) << "not a folder";
  BackgroundClusters unwritable(s, options_, folder_);
  unwritable.wait_for_build();
  EXPECT_EQ(unwritable.cache_result().outcome, CacheOutcome::Unwritable);
  EXPECT_NE(unwritable.take().stored_indices->in_memory(), nullptr);
  fs::remove(folder_);
}

// A write left for later that fails (the cache folder is a file) is reported, never thrown; the
// hierarchy handed on is whole.
TEST_F(ClusterCache, ALaterWriteThatFailsIsReported) {
  const Scene s = two_spheres();
  fs::create_directories(folder_);
  std::ofstream(folder_ / "a_file") << "not a folder";
  CacheResult result;
  StageTimes times;
  PendingCacheWrite later;
  const MeshClusters c =
      cached_mesh_clusters(s, options_, folder_ / "a_file", &times, &result, &later);
  EXPECT_TRUE(later.pending());
  EXPECT_EQ(result.outcome, CacheOutcome::Off); // nothing written yet
  later.run(&times, &result);
  EXPECT_FALSE(later.pending());
  EXPECT_EQ(result.outcome, CacheOutcome::Unwritable);
  EXPECT_FALSE(result.reason.empty());
  EXPECT_EQ(times.stages().back().first, "cache write");
  EXPECT_NE(c.stored_indices->in_memory(), nullptr); // no file to read them from
  EXPECT_TRUE(same(c, build_mesh_clusters(s, options_)));
}

TEST_F(ClusterCache, TheRasterTakesABuildBesideIt) {
  const auto [s, vpls, view] = sphere_box();
  RasterOptions o;
  o.interleave = 1;
  o.hierarchy_cache.clear();
  const Image own = RasterRenderer(s, o).render(view, vpls);
  const auto has = [](const StageTimes& t, const std::string& name) {
    for (const auto& [n, seconds] : t.stages())
      if (n == name) return true;
    return false;
  };
  const ClusterOptions shadow = shadow_cluster_options(o.shadow_lod);
  o.hierarchy_build = std::make_shared<BackgroundClusters>(s, shadow, fs::path());
  RasterRenderer taking(s, o);
  EXPECT_TRUE(taking.render(view, vpls).pixels() == own.pixels());
  EXPECT_TRUE(has(taking.setup_times(), "hierarchy wait"));
  EXPECT_FALSE(has(taking.setup_times(), "hierarchy levels"));
  EXPECT_TRUE(has(taking.hierarchy_beside_times(), "hierarchy levels"));
  EXPECT_FALSE(o.hierarchy_build->builds(s, shadow, fs::path())); // taken
  // A build of other options (the Cull mode's) is left; the renderer builds its own.
  o.hierarchy_build = std::make_shared<BackgroundClusters>(s, ClusterOptions{0, false}, fs::path());
  RasterRenderer building(s, o);
  EXPECT_TRUE(building.render(view, vpls).pixels() == own.pixels());
  EXPECT_TRUE(has(building.setup_times(), "hierarchy levels"));
  EXPECT_TRUE(building.hierarchy_beside_times().stages().empty());
}

} // namespace IRAD_UNITY_ID
} // namespace irad
