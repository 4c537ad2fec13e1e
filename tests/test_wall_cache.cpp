// The thinnest-wall scan's cache (walk/walls/wall_cache.h): a scan written once is read back with
// the same answer, for its reach or a shorter one; a longer reach, another scene, a truncated or a
// bit-flipped file is scanned again and written over, never trusted; scenes whose rays pass
// through alpha are not cached; irad::render reports what the cache did. The scan begun ahead
// (walk/walls/wall_scan_ahead.h) answers as the scan does, through the same cache, and one stopped
// before its answer was asked for keeps nothing.
#include "core/mesh/sphere_mesh.h"
#include "core/scene/scene_builder.h"
#include "irad/irad.h"
#include "test_rooms.h"
#include "walk/rays/ray_scene.h"
#include "walk/walls/thin_walls.h"
#include "walk/walls/wall_cache.h"
#include "walk/walls/wall_scan_ahead.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

namespace irad {
namespace IRAD_UNITY_ID {

namespace fs = std::filesystem;
using test_support::add_room;

// A room with an outward-facing slab of thickness `gap` inside: a wall of that gap.
Scene room_with_slab(float gap) {
  Scene s;
  s.source = "room_with_slab";
  const std::uint32_t m = add_material(s, glm::vec3(0.5f));
  add_room(s, glm::vec3(-1.0f), glm::vec3(1.0f), m);
  const std::size_t first = s.triangles.size();
  add_room(s, glm::vec3(-0.5f, 0.0f, -0.5f), glm::vec3(0.5f, gap, 0.5f), m);
  for (std::size_t t = first; t < s.triangles.size(); ++t)
    std::swap(s.triangles[t].y, s.triangles[t].z);
  finish(s);
  return s;
}

class WallCache : public ::testing::Test {
protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("irad_wall_cache_" + std::to_string(::getpid()));
    fs::remove_all(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }

  // The one .wall file in the folder.
  fs::path file() const {
    for (const fs::directory_entry& e : fs::directory_iterator(folder_))
      if (e.path().extension() == ".wall") return e.path();
    return {};
  }
  float scan(const Scene& s, const RayScene& rays, float up_to, CacheResult& result) const {
    return cached_thinnest_wall(s, rays, up_to, folder_, &result);
  }

  fs::path folder_;
};

TEST_F(WallCache, AScanIsReadBackForItsReachOrAShorterOne) {
  const Scene s = room_with_slab(0.01f);
  const RayScene rays(s);
  const float exact = thinnest_wall(s, rays, 0.5f);
  ASSERT_NEAR(exact, 0.01f / s.bounds.diagonal(), 1e-4f);
  CacheResult r;
  EXPECT_EQ(scan(s, rays, 0.5f, r), exact);
  EXPECT_EQ(r.outcome, CacheOutcome::Written);
  EXPECT_EQ(fs::file_size(file()), 48u);
  EXPECT_EQ(scan(s, rays, 0.5f, r), exact);
  EXPECT_EQ(r.outcome, CacheOutcome::Hit);
  // A shorter reach than the gap: the reach itself, as thinnest_wall answers.
  EXPECT_EQ(scan(s, rays, 0.5f * exact, r), thinnest_wall(s, rays, 0.5f * exact));
  EXPECT_EQ(r.outcome, CacheOutcome::Hit);
}

TEST_F(WallCache, ALongerReachScansAgain) {
  const Scene s = room_with_slab(0.4f); // thicker than 0.05 of the diagonal
  const RayScene rays(s);
  CacheResult r;
  EXPECT_EQ(scan(s, rays, 0.05f, r), 0.05f);
  EXPECT_EQ(r.outcome, CacheOutcome::Written);
  const float exact = thinnest_wall(s, rays, 0.5f);
  EXPECT_LT(exact, 0.5f);
  EXPECT_EQ(scan(s, rays, 0.5f, r), exact);
  EXPECT_EQ(r.outcome, CacheOutcome::Rebuilt);
  EXPECT_EQ(r.reason, "scanned to a shorter reach");
  EXPECT_EQ(scan(s, rays, 0.05f, r), 0.05f);
  EXPECT_EQ(r.outcome, CacheOutcome::Hit);
}

TEST_F(WallCache, AnotherSceneHasAnotherFile) {
  const Scene a = room_with_slab(0.01f), b = room_with_slab(0.02f);
  const RayScene rays_a(a), rays_b(b);
  CacheResult r;
  scan(a, rays_a, 0.5f, r);
  EXPECT_EQ(scan(b, rays_b, 0.5f, r), thinnest_wall(b, rays_b, 0.5f));
  EXPECT_EQ(r.outcome, CacheOutcome::Written);
  EXPECT_EQ(std::distance(fs::directory_iterator(folder_), fs::directory_iterator()), 2);
}

TEST_F(WallCache, ATruncatedOrBitFlippedFileIsScannedAgain) {
  const Scene s = room_with_slab(0.01f);
  const RayScene rays(s);
  const float exact = thinnest_wall(s, rays, 0.5f);
  CacheResult r;
  scan(s, rays, 0.5f, r);
  fs::resize_file(file(), 40);
  EXPECT_EQ(scan(s, rays, 0.5f, r), exact);
  EXPECT_EQ(r.outcome, CacheOutcome::Rebuilt);
  EXPECT_EQ(r.reason, "not the size of a wall file");
  // Every bit of the file flipped in turn: each is caught, the answer stays the scan's.
  for (int bit = 0; bit < 48 * 8; ++bit) {
    std::fstream f(file(), std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(bit / 8);
    char c = 0;
    f.get(c);
    f.seekp(bit / 8);
    f.put(static_cast<char>(c ^ (1 << (bit % 8))));
    f.close();
    ASSERT_EQ(scan(s, rays, 0.5f, r), exact) << bit;
    ASSERT_EQ(r.outcome, CacheOutcome::Rebuilt) << bit;
  }
  EXPECT_EQ(scan(s, rays, 0.5f, r), exact);
  EXPECT_EQ(r.outcome, CacheOutcome::Hit);
}

TEST_F(WallCache, AFolderThatCannotBeWrittenCostsOnlyTheWrite) {
  const Scene s = room_with_slab(0.01f);
  const RayScene rays(s);
  std::ofstream(folder_.string()) << "a file where the folder should be";
  CacheResult r;
  EXPECT_EQ(scan(s, rays, 0.5f, r), thinnest_wall(s, rays, 0.5f));
  EXPECT_EQ(r.outcome, CacheOutcome::Unwritable);
  EXPECT_NE(r.reason.find("cannot write"), std::string::npos) << r.reason;
  fs::remove(folder_);
}

TEST_F(WallCache, NoFolderOrAlphaIsNotCached) {
  Scene s = room_with_slab(0.01f);
  const RayScene rays(s);
  CacheResult r;
  EXPECT_EQ(cached_thinnest_wall(s, rays, 0.5f, {}, &r), thinnest_wall(s, rays, 0.5f));
  EXPECT_EQ(r.outcome, CacheOutcome::Off);
  s.materials.back().alpha_mode = AlphaMode::Mask;
  const RayScene masked(s);
  ASSERT_TRUE(masked.has_alpha());
  scan(s, masked, 0.5f, r);
  EXPECT_EQ(r.outcome, CacheOutcome::Off);
  EXPECT_FALSE(fs::exists(folder_));
}

TEST_F(WallCache, RenderReportsTheCache) {
  Log log([](const std::string&) {});
  Scene s = room_with_slab(0.01f);
  const std::uint32_t light = add_material(s, glm::vec3(0.5f), glm::vec3(5.0f));
  add_quad(s, {-0.3f, 0.999f, -0.3f}, {0.3f, 0.999f, -0.3f}, {0.3f, 0.999f, 0.3f},
           {-0.3f, 0.999f, 0.3f}, light);
  finish(s);
  s.cameras.push_back(look_at({0.0f, 0.5f, 0.9f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 1.2f));
  RenderOptions o;
  o.size = {32, 32};
  o.walk.paths = 8;
  o.raster.hierarchy_cache = folder_;
  o.raster.visibility = Visibility::Maps; // the planes are chosen where maps are drawn
  const RenderResult first = render(s, o, log);
  EXPECT_EQ(first.wall_cache, "written");
  const RenderResult second = render(s, o, log);
  EXPECT_EQ(second.wall_cache, "hit");
  EXPECT_EQ(second.thinnest_wall, first.thinnest_wall);
  EXPECT_EQ(second.shadow_planes, first.shadow_planes);
  o.raster.hierarchy_cache.clear();
  EXPECT_EQ(render(s, o, log).wall_cache, "off");
}

// room_with_slab with a sphere of about `triangles` triangles in its upper half: a scan of many
// rows.
Scene slab_and_sphere(float gap, std::size_t triangles) {
  Scene s = room_with_slab(gap);
  add_sphere(s, glm::vec3(0.0f, 0.6f, 0.0f), 0.3f, sphere_rings_for(triangles), 0);
  finish(s);
  return s;
}

// The scan's rows taken by any number of threads, joining at any time, give thinnest_wall's
// answer; a stop drops a row, and the scan then never counts as complete (so a stopped scan is
// never taken for an answer and written).
TEST(WallScan, RowsTakenByAnyThreadsGiveTheScansAnswer) {
  const Scene s = slab_and_sphere(0.01f, 20000);
  const RayScene rays(s);
  const float exact = thinnest_wall(s, rays, 0.5f, 1);
  ASSERT_NEAR(exact, 0.01f / s.bounds.diagonal(), 1e-4f);
  for (int threads : {1, 2, 5}) {
    WallScan scan(s, rays, 0.5f);
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back([&scan] { scan.work(); });
    scan.work();
    for (std::thread& t : pool) t.join();
    ASSERT_TRUE(scan.complete()) << threads;
    EXPECT_EQ(scan.result(), exact) << threads;
  }
  WallScan stopped(s, rays, 0.5f);
  const std::atomic<bool> stop{true};
  stopped.work(&stop);
  stopped.work();
  EXPECT_FALSE(stopped.complete());
}

TEST_F(WallCache, AScanAheadAnswersAsTheScanThroughTheCache) {
  const Scene s = slab_and_sphere(0.01f, 20000);
  const RayScene rays(s);
  const float exact = thinnest_wall(s, rays, 0.5f);
  CacheResult r;
  {
    WallScanAhead ahead(s, rays, 0.5f, folder_);
    EXPECT_EQ(ahead.get(&r), exact);
    EXPECT_EQ(r.outcome, CacheOutcome::Written);
    EXPECT_EQ(ahead.get(), exact); // asked again: the same
  }
  WallScanAhead again(s, rays, 0.5f, folder_);
  EXPECT_EQ(again.get(&r), exact);
  EXPECT_EQ(r.outcome, CacheOutcome::Hit);
  WallScanAhead uncached(s, rays, 0.5f, {});
  EXPECT_EQ(uncached.get(&r), exact);
  EXPECT_EQ(r.outcome, CacheOutcome::Off);
}

// Ended before its answer was asked for (a render whose visibility was traced): stopped within
// a row, nothing written. 600k triangles: the scan takes far longer than making and ending it.
TEST_F(WallCache, AScanAheadNotAskedForKeepsNothing) {
  const Scene s = slab_and_sphere(0.01f, 600000);
  const RayScene rays(s);
  { WallScanAhead ahead(s, rays, 0.5f, folder_); }
  EXPECT_TRUE(!fs::exists(folder_) || file().empty());
}

} // namespace IRAD_UNITY_ID
} // namespace irad
