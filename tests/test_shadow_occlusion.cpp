// Occlusion culling of the shadow faces' clusters (raster/shadow/shadow_occlusion.h,
// ShadowLodOptions::occlusion): the box test on a depth map made by hand, and on the GL that it
// changes no pixel while the faces draw less where walls hide most of a scene.
#include "core/camera/view.h"
#include "core/image/image_metrics.h"
#include "core/mesh/sphere_mesh.h"
#include "core/scene/scene_builder.h"
#include "raster/raster_renderer.h"
#include "raster/shadow/shadow_occlusion.h"
#include "tests/test_rooms.h"
#include "walk/vpls/quasi_random_walk.h"

#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace irad {
namespace IRAD_UNITY_ID {

Log quiet_log() {
  return Log([](const std::string&) {});
}

Bounds box(glm::vec3 lo, glm::vec3 hi) {
  Bounds b;
  b.lo = lo;
  b.hi = hi;
  return b;
}

// A 32^2 face from the origin looking down -z (90 degrees), far 10, every texel at depth 0.3
// (a sphere of radius 3 around the VPL, as distance / far) in a 32^2 atlas.
struct HandMadeFace {
  static constexpr int R = 32;
  glm::mat4 vp = glm::perspective(glm::radians(90.0f), 1.0f, 0.01f, 10.0f) *
                 glm::lookAt(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f), {0.0f, 1.0f, 0.0f});
  std::vector<float> depth = std::vector<float>(R * R, 0.3f);
  bool shows(const Bounds& b) const {
    const gl::FaceDepthBound bound(depth.data(), {R, R}, {0, 0}, {0, 0, R, R}, R);
    return bound.may_show(b, vp, R, glm::vec3(0.0f), 0.1f);
  }
};

TEST(ShadowOcclusion, ABoxBehindTheStoredDepthsIsHidden) {
  HandMadeFace face;
  const Bounds far_box = box({-1.0f, -1.0f, -6.0f}, {1.0f, 1.0f, -5.0f});  // 5 away: behind
  const Bounds near_box = box({-1.0f, -1.0f, -2.5f}, {1.0f, 1.0f, -2.0f}); // 2 away: in front
  EXPECT_FALSE(face.shows(far_box));
  EXPECT_TRUE(face.shows(near_box));
  // One texel in the far box's footprint with nothing stored (clear value 1): it may show.
  constexpr int R = HandMadeFace::R;
  face.depth[16 * R + 16] = 1.0f;
  EXPECT_TRUE(face.shows(far_box));
  // Outside its footprint's tiles (the box spans face pixels 12.8..19.2, texels 11..19 with the
  // texel of margin: tiles 1 and 2 of 8 texels): still hidden.
  face.depth[16 * R + 16] = 0.3f;
  face.depth[16 * R + 28] = 1.0f;
  EXPECT_FALSE(face.shows(far_box));
}

// A wall across the axis 3 away (the depths d_t = 0.3 / cos(theta_t)) and a box behind it off
// the axis (3.5..4 along it, 2..3.5 across): its nearest point (4.03 away) is nearer than what
// the outer texels of its footprint hold (up to 4.24), so only the axial bound hides it.
TEST(ShadowOcclusion, AWallSeenAtAnAngleHidesWhatIsBehindIt) {
  HandMadeFace face;
  constexpr int R = HandMadeFace::R;
  const auto ndc = [](int i) { return (2.0f * static_cast<float>(i) + 1.0f) / R - 1.0f; };
  for (int j = 0; j < R; ++j)
    for (int i = 0; i < R; ++i)
      face.depth[static_cast<std::size_t>(j * R + i)] =
          0.3f * std::sqrt(1.0f + ndc(i) * ndc(i) + ndc(j) * ndc(j));
  EXPECT_FALSE(face.shows(box({2.0f, -0.5f, -4.0f}, {3.5f, 0.5f, -3.5f})));
  // The same box moved in front of the wall (2.5..2.9 along the axis): it shows.
  EXPECT_TRUE(face.shows(box({2.0f, -0.5f, -2.9f}, {3.5f, 0.5f, -2.5f})));
}

TEST(ShadowOcclusion, BoxesOutsideTheFaceOrAcrossTheVplsPlane) {
  const HandMadeFace face;
  // Wholly outside the face's pyramid: no texel of the face, nothing to draw.
  EXPECT_FALSE(face.shows(box({20.0f, -1.0f, -6.0f}, {21.0f, 1.0f, -5.0f})));
  // Reaching behind the VPL's plane (w <= 0 at some corner): the projection is unbounded, kept.
  EXPECT_TRUE(face.shows(box({3.0f, -1.0f, -6.0f}, {4.0f, 1.0f, 1.0f})));
  // Holding the VPL: kept.
  EXPECT_TRUE(face.shows(box({-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f})));
}

using test_support::add_room;

// A closed room (a 2 m cube, its quads split 4^2 times) with the light and every VPL inside,
// and outside it, behind its +x wall, a sphere of 39600 triangles: the only face that sees the
// sphere (its box lies in no other face's pyramid) sees it behind the wall.
TEST(ShadowOcclusion, WhatAWallHidesIsNotDrawnAndNoPixelChanges) {
  Log log = quiet_log();
  Scene s;
  const std::uint32_t wall = add_material(s, glm::vec3(0.6f));
  const std::uint32_t light = add_material(s, glm::vec3(0.6f), glm::vec3(5.0f));
  add_room(s, {0.0f, 0.0f, 0.0f}, {2.0f, 2.0f, 2.0f}, wall);
  add_quad(s, {0.7f, 1.999f, 0.7f}, {1.3f, 1.999f, 0.7f}, {1.3f, 1.999f, 1.3f},
           {0.7f, 1.999f, 1.3f}, light);
  subdivide(s, 2);
  add_sphere(s, {3.5f, 1.0f, 1.0f}, 0.4f, 100, wall);
  finish(s);
  const RayScene rays(s);
  const VplSet vpls = quasi_random_walk(s, rays, {32, 64}, log);
  const View view = make_view(look_at({0.05f, 1.05f, 1.03f}, {2.0f, 0.9f, 1.0f}, {0, 1, 0}, 1.5f),
                              s.bounds, 64, 64);
  for (ShadowLodMode mode : {ShadowLodMode::Cull, ShadowLodMode::On}) {
    Image images[2];
    std::size_t drawn[2] = {};
    for (int occlusion = 0; occlusion < 2; ++occlusion) {
      RasterOptions o;
      o.interleave = 1;
      o.shadow_lod = {mode, 0.5f, occlusion == 1};
      RasterTimings t;
      images[occlusion] = RasterRenderer(s, o).render(view, vpls, &t);
      drawn[occlusion] = t.shadow_triangles;
    }
    const char* name = mode == ShadowLodMode::Cull ? "cull" : "on";
    std::printf("room and sphere, %s, %zu VPLs: %zu triangles drawn without occlusion culling, "
                "%zu with\n",
                name, vpls.vpls.size(), drawn[0], drawn[1]);
    EXPECT_TRUE(images[0].pixels() == images[1].pixels()) << name; // the same bits
    EXPECT_GT(drawn[1], 0u) << name;
    // Measured (llvmpipe, 64^2 faces, 75 VPLs): cull 2.77M -> 70.6k triangles. With LOD the
    // sphere is a whole-sphere level from the VPLs' distance: 25.6k triangles, 341 per VPL,
    // too few for the readbacks (ShadowAtlas::kOcclusionTrianglesPerVpl): drawn as they are.
    if (mode == ShadowLodMode::Cull)
      EXPECT_LT(drawn[1], drawn[0] / 20) << name;
    else
      EXPECT_EQ(drawn[1], drawn[0]) << name;
  }
}

} // namespace IRAD_UNITY_ID
} // namespace irad
