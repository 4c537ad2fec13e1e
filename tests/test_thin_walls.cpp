// The thinnest wall (walk/walls/thin_walls.h) and the occluder planes' automatic choice
// (raster_renderer.h planes_needed, irad::choose_shadow_planes): walls of two back-to-back faces
// at their gap whatever the scene's scale, coincident faces of opposite winding (a zero-thickness
// wall) and double-sided surfaces at 0; one-sided faces with nothing behind them, a panel under a
// ceiling and closed solids thicker than a few texels not at all. The Cornell box needs no planes
// at any resolution the raster picks; the two rooms of tests/test_two_rooms.cpp need them.
#include "core/scene/scene_builder.h"
#include "irad/irad.h"
#include "raster/raster_renderer.h"
#include "test_rooms.h"
#include "tests/test_paths.h"
#include "walk/rays/ray_scene.h"
#include "walk/walls/thin_walls.h"

#include <gtest/gtest.h>
#include <string>

namespace irad {
namespace IRAD_UNITY_ID {

using test_support::add_room;

// Two 2 m rooms side by side with a double wall of `gap` between them (x in [2, 2 + gap]),
// times k, with a light panel 1 mm under room A's ceiling.
Scene two_rooms(float gap, float k = 1.0f) {
  Scene s;
  s.source = "two_rooms";
  const std::uint32_t wall = add_material(s, glm::vec3(0.6f));
  const std::uint32_t light = add_material(s, glm::vec3(0.6f), glm::vec3(5.0f));
  add_room(s, glm::vec3(0.0f), k * glm::vec3(2.0f), wall);
  add_room(s, k * glm::vec3(2.0f + gap, 0.0f, 0.0f), k * glm::vec3(4.0f + gap, 2.0f, 2.0f), wall);
  add_quad(s, k * glm::vec3(0.7f, 1.999f, 0.7f), k * glm::vec3(1.3f, 1.999f, 0.7f),
           k * glm::vec3(1.3f, 1.999f, 1.3f), k * glm::vec3(0.7f, 1.999f, 1.3f), light);
  finish(s);
  return s;
}

float thinnest(const Scene& s, float up_to = 0.5f) {
  const RayScene rays(s);
  return thinnest_wall(s, rays, up_to, 2);
}

TEST(ThinWalls, ADoubleWallMeasuresItsGapAtAnyScale) {
  for (const float k : {1.0f, 10.0f, 0.1f}) {
    const Scene s = two_rooms(0.002f, k);
    const float expected = 0.002f * k / s.bounds.diagonal();
    // Measured: the rays' hit distances give the gap to float precision (relative 1e-6 here);
    // 1 % is the ray offsets' share at the largest scale.
    EXPECT_NEAR(thinnest(s), expected, 0.01f * expected) << k;
  }
  // 0.4 m between the rooms: thicker than anything looked for (up_to 0.05 of the diagonal).
  EXPECT_EQ(thinnest(two_rooms(0.4f), 0.05f), 0.05f);
}

TEST(ThinWalls, CoincidentFacesOfOppositeWindingAreAWallOfNoThickness) {
  Scene s;
  const std::uint32_t m = add_material(s, glm::vec3(0.5f));
  add_room(s, glm::vec3(-1.0f), glm::vec3(1.0f), m);
  // A wall at x = 0 facing +x, and the same plane facing -x in another tessellation (4 quads).
  add_quad(s, {0, -1, -1}, {0, 1, -1}, {0, 1, 1}, {0, -1, 1}, m);
  for (const float y0 : {-1.0f, 0.0f})
    for (const float z0 : {-1.0f, 0.0f})
      add_quad(s, {0, y0, z0}, {0, y0, z0 + 1}, {0, y0 + 1, z0 + 1}, {0, y0 + 1, z0}, m);
  finish(s);
  EXPECT_EQ(thinnest(s), 0.0f);
}

TEST(ThinWalls, ADoubleSidedSurfaceIsAWallOfNoThickness) {
  Scene s;
  const std::uint32_t m = add_material(s, glm::vec3(0.5f));
  const std::uint32_t two = add_material(s, glm::vec3(0.5f), {}, true);
  add_room(s, glm::vec3(-1.0f), glm::vec3(1.0f), m);
  EXPECT_EQ(thinnest(s), 0.5f); // a closed room alone: no wall
  add_quad(s, {0, -1, -1}, {0, 1, -1}, {0, 1, 1}, {0, -1, 1}, two);
  finish(s);
  EXPECT_EQ(thinnest(s), 0.0f);
}

TEST(ThinWalls, AThinSlabIsAWallAndAStackedPanelIsNot) {
  Scene s;
  const std::uint32_t m = add_material(s, glm::vec3(0.5f));
  // An outward-facing closed slab 0.01 thick: a room's faces turned around.
  Scene slab;
  add_room(slab, glm::vec3(0.0f), glm::vec3(1.0f, 0.01f, 1.0f),
           add_material(slab, glm::vec3(0.5f)));
  for (glm::uvec3& t : slab.triangles) std::swap(t.y, t.z);
  finish(slab);
  EXPECT_NEAR(thinnest(slab), 0.01f / slab.bounds.diagonal(), 1e-4f);
  // A panel 1 cm under a ceiling, both facing down: the ceiling faces the panel's back.
  add_quad(s, {0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, m);
  add_quad(s, {0, 0.99f, 0}, {1, 0.99f, 0}, {1, 0.99f, 1}, {0, 0.99f, 1}, m);
  finish(s);
  EXPECT_EQ(thinnest(s), 0.5f);
}

TEST(ThinWalls, TheCornellBoxNeedsNoPlanesAndTheTwoRoomsDo) {
  Log log([](const std::string&) {});
  const Scene box = load_scene(std::string(IRAD_SOURCE_DIR) + "/data/cornell_box.gltf", {}, log);
  const RayScene box_rays(box);
  const Scene rooms = two_rooms(0.002f);
  const RayScene room_rays(rooms);
  // The box's thinnest wall is a block (165 of a 959 mm diagonal): measured 0.172. Its light
  // panel, 0.1 mm under the ceiling, faces the same way as the ceiling and does not count.
  EXPECT_NEAR(thinnest_wall(box, box_rays, 0.5f), 0.172f, 0.002f);
  for (int r = 64; r <= 1024; r *= 2) {
    EXPECT_EQ(choose_shadow_planes(box, box_rays, ShadowPlanes::Auto, r).planes, ShadowPlanes::Off)
        << r;
    EXPECT_EQ(choose_shadow_planes(rooms, room_rays, ShadowPlanes::Auto, r).planes,
              ShadowPlanes::On)
        << r;
  }
  // At 16 texels per face edge a texel's depth range spans a block: the box needs them too.
  EXPECT_TRUE(planes_needed(0.172f, 16));
  EXPECT_EQ(choose_shadow_planes(box, box_rays, ShadowPlanes::On, 512).planes, ShadowPlanes::On);
  EXPECT_EQ(choose_shadow_planes(rooms, room_rays, ShadowPlanes::Off, 512).planes,
            ShadowPlanes::Off);
  // What irad::render drew with shadow maps (the planes are chosen where maps are drawn).
  RenderOptions o;
  o.size = {32, 32};
  o.walk.paths = 8;
  o.raster.visibility = Visibility::Maps;
  EXPECT_FALSE(render(box, o, log).shadow_planes);
  Scene lit = rooms;
  lit.cameras.push_back(look_at({1.0f, 1.0f, 1.9f}, {1.0f, 1.0f, 0.0f}, {0, 1, 0}, 1.2f));
  EXPECT_TRUE(render(lit, o, log).shadow_planes);
}

bool scanned(const RenderResult& r) {
  for (const auto& [stage, seconds] : r.seconds.raster_setup)
    if (stage == "planes scan") return true;
  return false;
}

// The planes are chosen when shadow maps are first drawn to shade (RasterOptions::choose_planes),
// not before: an image whose visibility `auto` traces never scans, and one drawn with maps
// gives the image the choice's planes give when asked for from the start.
TEST(ThinWalls, PlanesAreChosenOnlyWhereMapsAreDrawn) {
  Log log([](const std::string&) {});
  RenderOptions o;
  o.size = {64, 64};
  o.raster.interleave = 1; // 4096 pixels per VPL: auto draws the rooms' shadows with maps
  o.walk.paths = 8;
  o.raster.hierarchy_cache.clear(); // scanned every time: nothing written
  Scene lit = two_rooms(0.002f);
  lit.cameras.push_back(look_at({1.0f, 1.0f, 1.9f}, {1.0f, 1.0f, 0.0f}, {0, 1, 0}, 1.2f));
  const RenderResult chosen = render(lit, o, log);
  ASSERT_EQ(chosen.visibility, "maps");
  EXPECT_TRUE(chosen.shadow_planes);
  EXPECT_TRUE(scanned(chosen));
  EXPECT_NEAR(chosen.thinnest_wall, 0.002f / lit.bounds.diagonal(), 1e-5f);
  RenderOptions on = o;
  on.raster.shadow_lod.planes = ShadowPlanes::On;
  const RenderResult asked = render(lit, on, log);
  EXPECT_FALSE(scanned(asked));
  EXPECT_TRUE(asked.image.pixels() == chosen.image.pixels());

  // The Cornell box at 16x16, every VPL on every pixel: its faces' 160 triangles per VPL against
  // 256 pixels, so auto traces (BatchedPasses::rays_pay) and nothing scans.
  const Scene box = load_scene(std::string(IRAD_SOURCE_DIR) + "/data/cornell_box.gltf", {}, log);
  RenderOptions small = o;
  small.size = {16, 16};
  small.raster.interleave = 1;
  const RenderResult traced = render(box, small, log);
  ASSERT_EQ(traced.visibility, "rays");
  EXPECT_FALSE(scanned(traced));
  EXPECT_EQ(traced.thinnest_wall, -1.0f);
  EXPECT_EQ(traced.wall_cache, "off");
  small.raster.visibility = Visibility::Rays;
  EXPECT_TRUE(render(box, small, log).image.pixels() == traced.image.pixels());
  small.raster.visibility = Visibility::Maps;
  const RenderResult mapped = render(box, small, log);
  EXPECT_TRUE(scanned(mapped));
  EXPECT_GT(mapped.thinnest_wall, 0.0f);
}

} // namespace IRAD_UNITY_ID
} // namespace irad
