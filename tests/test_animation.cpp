// glTF node animation: keyframe interpolation against hand-computed values, the animated
// Cornell box posed against its static twin, and the per-frame updates (Embree refit, GL vertex
// upload, cached shadow maps) against renderers built from scratch on the posed scene.
#include "core/animation/animation.h"
#include "core/animation/keyframes.h"
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/image/image_metrics.h"
#include "core/sampling/rng.h"
#include "raster/raster_renderer.h"
#include "tests/test_paths.h"
#include "walk/rays/ray_scene.h"
#include "walk/vpls/quasi_random_walk.h"

#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

namespace irad {
namespace IRAD_UNITY_ID {

const std::string kData = std::string(IRAD_SOURCE_DIR) + "/data/";

Keyframes vec_keys(Interpolation i, std::vector<float> t, std::vector<glm::vec4> v) {
  Keyframes k;
  k.interpolation = i;
  k.times = std::move(t);
  k.values = std::move(v);
  return k;
}

TEST(Keyframes, StepHoldsEachKeyUntilTheNext) {
  const Keyframes k =
      vec_keys(Interpolation::Step, {1, 2, 4}, {{1, 0, 0, 0}, {2, 0, 0, 0}, {3, 0, 0, 0}});
  EXPECT_EQ(k.sample(0.0f).x, 1.0f); // before the first key
  EXPECT_EQ(k.sample(1.999f).x, 1.0f);
  EXPECT_EQ(k.sample(2.0f).x, 2.0f);
  EXPECT_EQ(k.sample(3.9f).x, 2.0f);
  EXPECT_EQ(k.sample(9.0f).x, 3.0f); // after the last
  EXPECT_EQ(k.sample(std::nanf("")).x, 1.0f);
}

TEST(Keyframes, LinearInterpolatesAndClamps) {
  const Keyframes k = vec_keys(Interpolation::Linear, {0, 2}, {{0, 10, -2, 0}, {4, 20, 2, 0}});
  const glm::vec4 v = k.sample(0.5f);
  EXPECT_FLOAT_EQ(v.x, 1.0f);
  EXPECT_FLOAT_EQ(v.y, 12.5f);
  EXPECT_FLOAT_EQ(v.z, -1.0f);
  EXPECT_FLOAT_EQ(k.sample(5.0f).y, 20.0f);
}

TEST(Keyframes, LinearRotationIsSlerpAlongTheShorterArc) {
  Keyframes k = vec_keys(Interpolation::Linear, {0, 1}, {{0, 0, 0, 1}, {0, 1, 0, 0}}); // 0 -> 180 y
  k.rotation = true;
  const glm::vec4 q = k.sample(0.5f); // 90 degrees about y
  EXPECT_NEAR(q.y, std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(q.w, std::sqrt(0.5f), 1e-6f);
  // -q is the same rotation: slerp must not take the long way round (through 180 degrees).
  k.values[1] = {0, -std::sin(0.3f), 0, -std::cos(0.3f)}; // 0.6 rad about y, negated
  const glm::vec4 r = k.sample(0.5f);
  EXPECT_NEAR(std::abs(r.w), std::cos(0.15f), 1e-5f);
}

TEST(Keyframes, CubicSplineIsTheHermiteSplineOfTheFile) {
  // Keys (t, v): (0, 0) and (2, 1); out-tangent of key 0: 3, in-tangent of key 1: -1.
  const Keyframes k = vec_keys(
      Interpolation::CubicSpline, {0, 2},
      {{9, 0, 0, 0}, {0, 0, 0, 0}, {3, 0, 0, 0}, {-1, 0, 0, 0}, {1, 0, 0, 0}, {9, 0, 0, 0}});
  for (float t : {0.0f, 0.5f, 1.0f, 1.7f, 2.0f}) {
    const float s = t / 2.0f, d = 2.0f;
    const float expected = (-2 * s * s * s + 3 * s * s) * 1.0f +
                           d * (s * s * s - 2 * s * s + s) * 3.0f + d * (s * s * s - s * s) * -1.0f;
    EXPECT_NEAR(k.sample(t).x, expected, 1e-6f) << "t = " << t;
  }
  EXPECT_EQ(k.sample(-1.0f).x, 0.0f); // the value of the first key, not its tangent
  EXPECT_EQ(k.sample(3.0f).x, 1.0f);
}

struct AnimatedBox {
  Log log{[](const std::string&) {}};
  Scene still = load_gltf(kData + "cornell_box.gltf", log);
  Scene scene = load_gltf(kData + "cornell_animated.gltf", log);
};

float max_distance(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  float d = 0.0f;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, glm::length(a[i] - b[i]));
  return d;
}

TEST(AnimatedScene, LoadsTheTracksAndPosesTheRestAtTimeZero) {
  AnimatedBox box;
  ASSERT_TRUE(box.scene.animation);
  const Animation& anim = *box.scene.animation;
  EXPECT_EQ(anim.tracks.size(), 6u);
  EXPECT_EQ(anim.parts.size(), 3u); // short block, tall block, light
  EXPECT_FLOAT_EQ(anim.start(), 0.0f);
  EXPECT_FLOAT_EQ(anim.end(), 10.0f);
  ASSERT_EQ(box.scene.positions.size(), box.still.positions.size());
  Scene posed = box.scene;
  anim.pose(0.0f, posed);
  // The pivot/offset hierarchy and float round trips: 2 nm on a 0.55 m box.
  EXPECT_LT(max_distance(posed.positions, box.still.positions), 1e-6f);
  EXPECT_LT(glm::length(posed.cameras[0].position() - box.still.cameras[0].position()), 1e-6f);
  // Static triangles never move.
  anim.pose(7.3f, posed);
  EXPECT_EQ(posed.positions[0], box.still.positions[0]); // the floor
}

TEST(AnimatedScene, PoseMatchesTheKeysOfTheFile) {
  AnimatedBox box;
  const Animation& anim = *box.scene.animation;
  Scene posed = box.scene;
  // t = 5 s: the short block turned 90 degrees about the vertical through its centre (x_c, z_c),
  // and moved by (-0.06, 0, 0.04); the tall block jumped 0.08 in x; the light is at -0.05 in x
  // (halfway from +0.1 at 2.5 s to -0.1 at 7.5 s).
  anim.pose(5.0f, posed);
  const Animation::MeshPart* short_block = nullptr;
  for (const auto& p : anim.parts)
    if (p.vertices.size() == 20 && box.still.positions[p.vertices[0]].y < 0.2f &&
        box.still.positions[p.vertices[0]].x < 0.3f)
      short_block = &p;
  ASSERT_NE(short_block, nullptr);
  Bounds b;
  for (std::uint32_t v : short_block->vertices) b.extend(box.still.positions[v]);
  const glm::vec3 c(b.center().x, 0.0f, b.center().z);
  for (std::uint32_t v : short_block->vertices) {
    const glm::vec3 p = box.still.positions[v] - c;
    const glm::vec3 turned(p.z, p.y, -p.x); // +90 degrees about +y
    const glm::vec3 expected = c + turned + glm::vec3(-0.06f, 0.0f, 0.04f);
    EXPECT_LT(glm::length(posed.positions[v] - expected), 1e-6f);
  }
  // Normals turn with the block and stay unit.
  const std::uint32_t v0 = short_block->vertices[4];
  const glm::vec3 n = box.still.normals[v0];
  EXPECT_LT(glm::length(posed.normals[v0] - glm::vec3(n.z, n.y, -n.x)), 1e-6f);
  // The camera's position at t = 3 s is its key.
  anim.pose(3.0f, posed);
  EXPECT_LT(glm::length(posed.cameras[0].position() - glm::vec3(0.20f, 0.26f, -0.45f)), 1e-6f);
}

TEST(AnimatedScene, BoundsHoldEveryPose) {
  AnimatedBox box;
  Scene posed = box.scene;
  const Bounds& b = box.scene.bounds;
  const float slack = 1e-6f * b.diagonal();
  for (float t = 0.0f; t <= 10.0f; t += 0.05f) {
    box.scene.animation->pose(t, posed);
    for (const glm::vec3& p : posed.positions) {
      ASSERT_TRUE(glm::all(glm::greaterThanEqual(p, b.lo - slack))) << "t = " << t;
      ASSERT_TRUE(glm::all(glm::lessThanEqual(p, b.hi + slack))) << "t = " << t;
    }
  }
}

// The refitted BVH answers every ray as a BVH built from scratch on the posed scene.
TEST(AnimatedScene, EmbreeRefitAgreesWithAFreshBuild) {
  AnimatedBox box;
  Scene& scene = box.scene;
  RayScene rays(scene);
  std::vector<char> moving_vertex(scene.positions.size(), 0);
  for (const auto& part : scene.animation->parts)
    for (std::uint32_t v : part.vertices) moving_vertex[v] = 1;
  Pcg32 rng(7, 1);
  const auto u = [&] { return static_cast<float>(rng.next_double()); };
  int moving_hits = 0;
  for (float t : {2.0f, 5.0f, 8.5f}) {
    scene.animation->pose(t, scene);
    rays.update(scene);
    Scene fresh_scene = scene;
    fresh_scene.animation = nullptr;
    const RayScene fresh(fresh_scene);
    for (int i = 0; i < 2000; ++i) {
      const glm::vec3 o =
          scene.bounds.lo + (scene.bounds.hi - scene.bounds.lo) * glm::vec3(u(), u(), u());
      const glm::vec3 d = glm::normalize(glm::vec3(u(), u(), u()) - 0.5f);
      const auto a = rays.intersect(o, d, 0.0f, 10.0f);
      const auto e = fresh.intersect(o, d, 0.0f, 10.0f);
      ASSERT_EQ(a.has_value(), e.has_value());
      if (!a) continue;
      EXPECT_EQ(a->triangle, e->triangle);
      EXPECT_NEAR(a->t, e->t, 1e-6f * e->t);
      moving_hits += moving_vertex[scene.triangles[a->triangle].x];
    }
  }
  std::printf("rays hitting moved triangles: %d of 6000\n", moving_hits);
  EXPECT_GT(moving_hits, 300); // the test does exercise the refitted geometry
}

// A renderer that uploaded the moved vertices draws what a renderer built on the posed scene
// draws; shading cached shadow maps equals drawing them again (same VPLs, same camera).
TEST(AnimatedScene, RasterUpdateAndCachedShadowMapsMatchAFreshRender) {
  AnimatedBox box;
  Scene& scene = box.scene;
  RayScene rays(scene);
  RasterOptions o;
  o.shadow_resolution = 64;
  RasterRenderer updated(scene, o);
  scene.animation->pose(6.0f, scene);
  rays.update(scene);
  updated.scene_changed();
  const QuasiRandomWalk walk(scene, rays, {32, 64}, box.log);
  VplSet vpls = walk.header();
  for (std::uint32_t i = 0; i < 32; ++i) walk.trace(i, vpls.vpls);
  const View view = make_view(scene.cameras[0], scene.bounds, 64, 64);
  Scene posed = scene;
  posed.animation = nullptr;
  const Image fresh = RasterRenderer(posed, o).render(view, vpls);
  const ImageMetrics m = compare_images(updated.render(view, vpls), fresh);
  std::printf("updated vs fresh renderer: relMSE %.3g, max %.3g\n", m.relmse, m.max_abs_error);
  EXPECT_LT(m.max_abs_error, 1e-6); // measured 0: the same draws on the same vertices

  updated.cache_path(0, vpls.vpls, 64, 64);
  const ImageMetrics c = compare_images(updated.render_cached(view), fresh);
  std::printf("cached shadow maps vs fresh renderer: relMSE %.3g, max %.3g\n", c.relmse,
              c.max_abs_error);
  EXPECT_LT(c.max_abs_error, 1e-6);
}

} // namespace IRAD_UNITY_ID
} // namespace irad
