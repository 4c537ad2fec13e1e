// RayScene's (walk/rays/ray_scene.h) queries agree however they are asked. The BVH's two qualities
// (BvhQuality): over a closed room with a finely tessellated sphere inside, random rays from
// inside the room hit in both, at the same distance and, but for ties at one distance, on the
// same triangle; shadow segments agree. High (spatial splits) is the reference the estimators
// were measured with. Packets of segments of any origins: the same hits as one at a time.
#include "core/mesh/sphere_mesh.h"
#include "core/sampling/rng.h"
#include "core/scene/scene_builder.h"
#include "test_rooms.h"
#include "walk/rays/ray_scene.h"

#include <cmath>
#include <gtest/gtest.h>
#include <optional>
#include <vector>

namespace irad {
namespace IRAD_UNITY_ID {

glm::vec3 random_direction(Pcg32& rng) {
  const float z = static_cast<float>(2.0 * rng.next_double() - 1.0);
  const float phi = static_cast<float>(6.283185307179586 * rng.next_double());
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

glm::vec3 random_point_in_room(Pcg32& rng) {
  return {static_cast<float>(1.9 * rng.next_double() - 0.95),
          static_cast<float>(1.9 * rng.next_double() - 0.95),
          static_cast<float>(1.9 * rng.next_double() - 0.95)};
}

// A closed 2 m room with a sphere of 57,120 triangles inside.
Scene room_with_sphere() {
  Scene s;
  const std::uint32_t m = add_material(s, glm::vec3(0.5f));
  test_support::add_room(s, glm::vec3(-1.0f), glm::vec3(1.0f), m);
  add_sphere(s, glm::vec3(0.2f, -0.1f, 0.1f), 0.4f, 120, m);
  finish(s);
  return s;
}

TEST(RayQueries, FastAndHighBvhAnswerTheSameRays) {
  const Scene s = room_with_sphere();
  const RayScene high(s, BvhQuality::High), fast(s, BvhQuality::Fast);
  ASSERT_EQ(high.epsilon(), fast.epsilon());
  Pcg32 rng(7, 1);
  int other_triangle = 0, blocked_differs = 0;
  constexpr int kRays = 20000;
  for (int k = 0; k < kRays; ++k) {
    const glm::vec3 o = random_point_in_room(rng);
    const glm::vec3 d = random_direction(rng);
    const auto a = high.intersect(o, d, 0.0f, 10.0f);
    const auto b = fast.intersect(o, d, 0.0f, 10.0f);
    // A closed room: every ray hits something, whatever the BVH (both are watertight).
    ASSERT_TRUE(a && b) << k;
    // The same triangle test on the same vertices: the same distance to float precision.
    ASSERT_NEAR(a->t, b->t, 1e-6f * std::max(1.0f, a->t)) << k;
    if (a->triangle != b->triangle) ++other_triangle;
    const float tmax = static_cast<float>(3.0 * rng.next_double());
    if (high.occluded(o, d, 0.0f, tmax) != fast.occluded(o, d, 0.0f, tmax)) ++blocked_differs;
  }
  // Measured 0 of 20,000; a tie (a ray through an edge shared by two triangles) may go either
  // way, so a few in a thousand are allowed.
  EXPECT_LE(other_triangle, kRays / 500);
  EXPECT_LE(blocked_differs, kRays / 500);
}

TEST(RayQueries, PacketsOfSegmentsAnswerAsOneAtATime) {
  const Scene s = room_with_sphere();
  const RayScene rays(s);
  Pcg32 rng(11, 2);
  // 1001 segments (not a multiple of the packets' 8), some too short to reach anything, some
  // starting where others end.
  std::vector<RaySegment> segments(1001);
  for (RaySegment& g : segments) {
    g.origin = random_point_in_room(rng);
    g.direction = random_direction(rng);
    g.tmin = static_cast<float>(0.1 * rng.next_double());
    g.tmax = g.tmin + static_cast<float>(2.0 * rng.next_double());
  }
  std::vector<std::optional<RayHit>> hits(segments.size());
  rays.intersect(segments.data(), segments.size(), hits.data());
  int hit = 0;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const RaySegment& g = segments[i];
    const auto one = rays.intersect(g.origin, g.direction, g.tmin, g.tmax);
    ASSERT_EQ(one.has_value(), hits[i].has_value()) << i;
    if (!one) continue;
    ++hit;
    EXPECT_EQ(one->triangle, hits[i]->triangle) << i;
    EXPECT_NEAR(one->t, hits[i]->t, 1e-6f * std::max(1.0f, one->t)) << i;
    EXPECT_NEAR(one->bary.x, hits[i]->bary.x, 1e-5f) << i;
    EXPECT_NEAR(one->bary.y, hits[i]->bary.y, 1e-5f) << i;
  }
  EXPECT_GT(hit, 100); // both cases seen
  EXPECT_LT(hit, 1000);
}

// intersect_leaving: a segment leaving out the triangle it hit finds what lies beyond it (the
// hit of the same segment restarted past that point), and leaving out a triangle it does not hit
// changes nothing.
TEST(RayQueries, LeavingATriangleOutFindsWhatLiesBeyondIt) {
  const Scene s = room_with_sphere();
  const RayScene rays(s);
  Pcg32 rng(12, 3);
  std::vector<RaySegment> segments;
  std::vector<std::uint32_t> own, other;
  std::vector<std::optional<RayHit>> first;
  while (segments.size() < 1001) {
    RaySegment g{random_point_in_room(rng), random_direction(rng), 0.0f, 4.0f};
    const auto hit = rays.intersect(g.origin, g.direction, g.tmin, g.tmax);
    if (!hit) continue;
    segments.push_back(g);
    own.push_back(hit->triangle);
    other.push_back((hit->triangle + 1) % std::uint32_t(s.triangle_count()));
    first.push_back(hit);
  }
  std::vector<std::optional<RayHit>> beyond(segments.size()), same(segments.size());
  rays.intersect_leaving(segments.data(), own.data(), segments.size(), beyond.data());
  rays.intersect_leaving(segments.data(), other.data(), segments.size(), same.data());
  int compared = 0;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const RaySegment& g = segments[i];
    if (other[i] != first[i]->triangle && same[i]) { // (a tie may give the other triangle)
      EXPECT_EQ(same[i]->triangle, first[i]->triangle) << i;
      EXPECT_EQ(same[i]->t, first[i]->t) << i;
    }
    const auto restarted = rays.intersect(g.origin, g.direction, first[i]->t + 1e-4f, g.tmax);
    if (beyond[i]) {
      EXPECT_NE(beyond[i]->triangle, own[i]) << i;
      EXPECT_GE(beyond[i]->t, first[i]->t) << i;
      if (beyond[i]->t < first[i]->t + 1e-3f) continue; // a neighbour at the same point
    }
    ASSERT_EQ(restarted.has_value(), beyond[i].has_value()) << i; // past a wall: nothing
    if (restarted) {
      EXPECT_EQ(restarted->triangle, beyond[i]->triangle) << i;
    }
    ++compared;
  }
  EXPECT_GT(compared, 900);
}

} // namespace IRAD_UNITY_ID
} // namespace irad
