// Hard cases of the estimators: degenerate albedos (rho_bar = 0 and 1), extreme path counts, the
// scene's scale, VPLs in corners, and the float accumulation of many passes (a thin wall between
// a lit and a dark room: tests/test_two_rooms.cpp). Every bound below is a measured value with a
// stated margin.
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/image/image_metrics.h"
#include "core/lights/light_sampler.h"
#include "core/sampling/particle_counts.h"
#include "core/sampling/radical_inverse.h"
#include "core/scene/scene_builder.h"
#include "raster/context/gl_context.h"
#include "raster/context/shader_program.h"
#include "raster/image/target.h"
#include "raster/raster_renderer.h"
#include "tests/raster_test_options.h"
#include "tests/test_paths.h"
#include "walk/estimators/path_tracer.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/vpls/quasi_random_walk.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <gtest/gtest.h>
#include <numbers>
#include <string>
#include <vector>

namespace irad {
namespace IRAD_UNITY_ID {

constexpr double pi = std::numbers::pi;

Log quiet_log() {
  return Log([](const std::string&) {});
}

using test_support::interleaves;
using test_support::raster_options;

// Radiant power of a VPL's emission profile (as tests/test_walk.cpp): pi I (surface), 2 pi I
// (two-sided), 4 pi I (point).
double vpl_power(const Vpl& v) {
  const double mean = (double(v.intensity.x) + v.intensity.y + v.intensity.z) / 3.0;
  switch (v.kind) {
  case VplKind::Surface:
    return pi * mean;
  case VplKind::TwoSided:
    return 2.0 * pi * mean;
  case VplKind::Point:
    return 4.0 * pi * mean;
  case VplKind::Spot:
  case VplKind::Directional:
    break;
  }
  return 0.0;
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

double max_red(const Image& image) {
  double m = 0.0;
  for (const glm::vec4& p : image.pixels()) m = std::max(m, double(p.r));
  return m;
}

double mean_rgb(const Image& image) {
  double sum = 0.0;
  for (const glm::vec4& p : image.pixels()) sum += double(p.r) + p.g + p.b;
  return sum / (3.0 * static_cast<double>(image.pixels().size()));
}

// ---------------------------------------------------------------------------------------------
// 1. rho_bar = 0: no reflection at all.

TEST(HardCases, ZeroAlbedoLeavesOnlyDepthZeroAndTheEmitters) {
  Log log = quiet_log();
  const float radiance = 2.0f;
  const Scene s = closed_box(1.0f, 0.0f, 0.3f, radiance);
  const RayScene rays(s);
  const std::uint32_t n = 64;
  const VplSet set = quasi_random_walk(s, rays, {n, 64}, log);
  EXPECT_EQ(set.rho_bar, 0.0);
  EXPECT_EQ(set.l_max, 0);
  EXPECT_FALSE(set.depth_capped);
  ASSERT_EQ(set.vpls.size(), n);
  for (const Vpl& v : set.vpls) {
    EXPECT_EQ(v.depth, 0);
    EXPECT_TRUE(finite(v.intensity));
  }

  // Inside the box, looking up at the light patch and two walls.
  const Camera camera = look_at({0.2f, 0.25f, 0.85f}, {0.5f, 0.9f, 0.5f}, {0, 1, 0}, 1.2f);
  const View view = make_view(camera, s.bounds, 48, 48);
  for (int k : interleaves) {
    RasterRenderer raster(s, raster_options(64, 0.05f, k));
    const Image image = raster.render(view, set);
    const Image emitters_only = raster.render(view, VplSet{});
    EXPECT_EQ(image.non_finite_count(), 0u) << k;
    // Every VPL pass adds rho(x) = 0 times a finite number: exactly nothing.
    EXPECT_TRUE(image.pixels() == emitters_only.pixels()) << k;
    std::size_t lit = 0, other = 0;
    for (const glm::vec4& p : image.pixels()) {
      if (p.r == radiance && p.g == radiance && p.b == radiance)
        ++lit;
      else if (p.r == 0.0f && p.g == 0.0f && p.b == 0.0f)
        ++other;
    }
    std::printf("rho_bar = 0, interleave %d: %zu pixels see the emitter (L_e exactly), %zu are "
                "exactly 0, of %zu\n",
                k, lit, other, image.pixels().size());
    EXPECT_EQ(lit + other, image.pixels().size()) << k;
    // Measured 125 and 2179 of 2304: the view holds both kinds of pixel.
    EXPECT_GT(lit, 100u) << k;
    EXPECT_GT(other, 2000u) << k;
  }

  // rt-vpl: the same (the emitter's pixels may differ at its edges, not in value).
  const Image traced = trace_vpls(s, rays, view, set, {0.05f, 0});
  for (const glm::vec4& p : traced.pixels())
    EXPECT_TRUE((p.r == 0.0f || p.r == radiance) && p.g == p.r && p.b == p.r) << p.r;
}

// ---------------------------------------------------------------------------------------------
// 2. rho_bar = 1: the walk would never end without its depth cap.

TEST(HardCases, AlbedoOneStopsAtTheDepthCapWithOneWarning) {
  int warnings = 0;
  std::string warning;
  Log log([&](const std::string& m) {
    ++warnings;
    warning = m;
  });
  const Scene s = closed_box(1.0f, 1.0f, 0.3f, 1.0f);
  const RayScene rays(s);
  WalkOptions options;
  options.paths = 4; // depth_cap: the default
  const VplSet set = quasi_random_walk(s, rays, options, log);
  std::printf("rho_bar = %.6f: l_max %d, %zu VPLs, warning: %s\n", set.rho_bar, set.l_max,
              set.vpls.size(), warning.c_str());
  EXPECT_EQ(set.rho_bar, 1.0);
  EXPECT_TRUE(set.depth_capped);
  EXPECT_EQ(set.l_max, options.depth_cap);
  EXPECT_EQ(warnings, 1);
  EXPECT_NE(warning.find("capped"), std::string::npos) << warning;
  // n_j = N for every j <= cap, and nothing escapes a closed box.
  const std::uint64_t expected = std::uint64_t(options.paths) * (options.depth_cap + 1);
  EXPECT_EQ(set.planned, expected);
  EXPECT_EQ(set.vpls.size(), expected);
  // Albedo 1: every depth carries the emitters' whole power (throughput is deterministic).
  const double phi = LightSampler(s).total_power();
  std::vector<double> power(static_cast<std::size_t>(set.l_max) + 1, 0.0);
  for (const Vpl& v : set.vpls) {
    ASSERT_TRUE(finite(v.intensity));
    ASSERT_LE(v.depth, options.depth_cap);
    power[v.depth] += vpl_power(v);
  }
  double worst = 0.0;
  for (double p : power) worst = std::max(worst, std::abs(p / phi - 1.0));
  std::printf("rho_bar = 1: power per depth / Phi off by at most %.3g\n", worst);
  // Measured 0 (every VPL of a depth carries Phi/N); 1e-6 allows float rounding of intensities.
  EXPECT_LT(worst, 1e-6);

  const Camera camera = look_at({0.3f, 0.4f, 0.9f}, {0.6f, 0.5f, 0.0f}, {0, 1, 0}, 1.3f);
  const View view = make_view(camera, s.bounds, 32, 32);
  for (int k : interleaves) {
    RasterRenderer raster(s, raster_options(64, 0.05f, k));
    const Image image = raster.render(view, set);
    // Measured: mean 0.767, max 2.22 (65 bounces of light that is never absorbed).
    std::printf("rho_bar = 1, interleave %d: raster mean %.4f, max %.4f\n", k, mean_rgb(image),
                max_red(image));
    EXPECT_EQ(image.non_finite_count(), 0u) << k;
    EXPECT_GT(mean_rgb(image), 0.0) << k;
  }
}

// ---------------------------------------------------------------------------------------------
// 3. Extreme path counts.

TEST(HardCases, OnePathRendersAFiniteImage) {
  Log log = quiet_log();
  const Scene s = closed_box(1.0f, 0.5f, 0.3f, 1.0f);
  const RayScene rays(s);
  const VplSet set = quasi_random_walk(s, rays, {1, 64}, log);
  EXPECT_EQ(set.l_max, 0); // n_1 = floor(0.5) = 0
  ASSERT_EQ(set.vpls.size(), 1u);
  const Camera camera = look_at({0.3f, 0.4f, 0.9f}, {0.6f, 0.5f, 0.0f}, {0, 1, 0}, 1.3f);
  const View view = make_view(camera, s.bounds, 32, 32);
  const Image traced = trace_vpls(s, rays, view, set, {0.05f, 0});
  EXPECT_EQ(traced.non_finite_count(), 0u);
  for (int k : interleaves) {
    RasterRenderer raster(s, raster_options(64, 0.05f, k));
    const Image image = raster.render(view, set);
    std::printf("N = 1, interleave %d: raster mean %.5f, rt-vpl mean %.5f\n", k, mean_rgb(image),
                mean_rgb(traced));
    EXPECT_EQ(image.non_finite_count(), 0u) << k;
    EXPECT_GT(mean_rgb(image), 0.0) << k;
  }
}

TEST(HardCases, FourMillionPathsInAClosedBox) {
  Log log = quiet_log();
  const Scene s = closed_box(1.0f, 0.5f, 0.3f, 1.0f);
  const RayScene rays(s);
  const std::uint32_t n = 1u << 22;
  const VplSet set = quasi_random_walk(s, rays, {n, 64}, log);
  const ParticleCounts counts(n, mean_albedo(s), 64);
  // rho_bar = 0.5 exactly: n_j = 2^(22-j), l_max = 22, M = 2^23 - 1 (~436 MB of VPLs).
  EXPECT_EQ(set.l_max, 22);
  EXPECT_EQ(set.planned, (std::uint64_t(1) << 23) - 1);
  EXPECT_EQ(set.vpls.size(), counts.vpl_count()); // nothing escapes a closed box
  std::vector<std::uint64_t> per_depth(23, 0);
  double depth0 = 0.0;
  bool all_finite = true;
  for (const Vpl& v : set.vpls) {
    all_finite = all_finite && finite(v.intensity) && finite(v.position) && finite(v.normal);
    if (v.depth < per_depth.size()) ++per_depth[v.depth];
    if (v.depth == 0) depth0 += vpl_power(v);
  }
  EXPECT_TRUE(all_finite);
  for (int j = 0; j <= 22; ++j) EXPECT_EQ(per_depth[j], counts.reaching(j)) << "depth " << j;
  const double phi = LightSampler(s).total_power();
  const double rel = std::abs(depth0 / phi - 1.0);
  std::printf("N = 2^22: %zu VPLs, depth-0 power / Phi - 1 = %.3g\n", set.vpls.size(),
              depth0 / phi - 1.0);
  // Measured 1.3e-11: each depth-0 VPL carries Phi/N up to float rounding (< 6e-8 relative).
  EXPECT_LT(rel, 1e-6);
}

// ---------------------------------------------------------------------------------------------
// 4. Scale invariance: every tolerance is a fraction of the bounding diagonal.

// The scene scaled by k about the origin: positions, camera positions and clip planes; radiance
// is unchanged, so a punctual light's intensity scales by k^2 (irradiance I / d^2).
Scene scaled(const Scene& scene, float k) {
  Scene s = scene;
  for (glm::vec3& p : s.positions) p *= k;
  for (Camera& c : s.cameras) {
    c.camera_to_world[3] = glm::vec4(k * glm::vec3(c.camera_to_world[3]), 1.0f);
    c.znear *= k;
    if (c.zfar) *c.zfar *= k;
  }
  for (PunctualLight& l : s.lights) {
    l.position *= k;
    if (l.kind != PunctualLight::Kind::Directional) l.intensity *= k * k; // E stays
  }
  finish(s);
  return s;
}

TEST(HardCases, CornellBoxRendersTheSameAtAnyScale) {
  Log log = quiet_log();
  const Scene base = load_gltf(std::string(IRAD_SOURCE_DIR) + "/data/cornell_box.gltf", log);
  const float scales[3] = {1.0f, 1e-3f, 1e4f};
  const char* names[3] = {"1", "1e-3", "1e4"};
  std::vector<Image> traced;                                        // per scale
  std::vector<std::vector<Image>> rastered(std::size(interleaves)); // per interleave, per scale
  std::vector<std::size_t> vpl_counts;
  for (float scale : scales) {
    const Scene s = scaled(base, scale);
    const RayScene rays(s);
    const VplSet set = quasi_random_walk(s, rays, {64, 64}, log);
    const View view = make_view(s.cameras.at(0), s.bounds, 64, 64);
    traced.push_back(trace_vpls(s, rays, view, set, {0.05f, 0}));
    vpl_counts.push_back(set.vpls.size());
    for (std::size_t i = 0; i < std::size(interleaves); ++i) {
      RasterRenderer raster(s, raster_options(256, 0.05f, interleaves[i]));
      rastered[i].push_back(raster.render(view, set));
      EXPECT_EQ(rastered[i].back().non_finite_count(), 0u) << scale;
    }
  }
  for (int j = 1; j < 3; ++j) {
    EXPECT_EQ(vpl_counts[j], vpl_counts[0]) << names[j];
    const ImageMetrics t = compare_images(traced[j], traced[0]);
    std::printf("scale %s vs 1: rt-vpl relMSE %.3g, mean ratio %.7f\n", names[j], t.relmse,
                t.mean_ratio[0]);
    // Measured (64x64, N = 64): relMSE 3.0e-8 and 1.5e-8, mean ratio 0.999973 and 0.999995 (a
    // few edge pixels whose pixel-centre ray hits the other surface). Bounds ~4x.
    EXPECT_LT(t.relmse, 1e-7) << names[j];
    EXPECT_NEAR(t.mean_ratio[0], 1.0, 1e-4) << names[j];
    for (std::size_t i = 0; i < std::size(interleaves); ++i) {
      const ImageMetrics r = compare_images(rastered[i][j], rastered[i][0]);
      std::printf("scale %s vs 1: raster (interleave %d) relMSE %.3g, mean ratio %.7f, max abs "
                  "%.3g\n",
                  names[j], interleaves[i], r.relmse, r.mean_ratio[0], r.max_abs_error);
      // Measured (llvmpipe, 256^2 faces): interleave 1 relMSE 2.8e-13 (1e-3) and 6.9e-10 (1e4),
      // interleave 4 3.1e-13 and 4.7e-13, mean ratios within 3e-7 of 1. Bounds ~100x; a
      // tolerance that is an absolute length instead of a fraction of the diagonal (shadow acne,
      // rays re-hitting their own surface, a resolve that rejects every neighbour) costs orders
      // more.
      EXPECT_LT(r.relmse, 1e-7) << names[j] << " interleave " << interleaves[i];
      EXPECT_NEAR(r.mean_ratio[0], 1.0, 1e-5) << names[j] << " interleave " << interleaves[i];
    }
  }
}

// ---------------------------------------------------------------------------------------------
// 5. VPLs exactly at a box's corners, on its edges and on its walls.

Vpl hand_vpl(const glm::vec3& position, const glm::vec3& normal, VplKind kind) {
  Vpl v;
  v.position = position;
  v.normal = glm::normalize(normal);
  v.intensity = glm::vec3(0.01f);
  v.kind = kind;
  return v;
}

VplSet corner_vpls() {
  VplSet set;
  set.paths = 1;
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 p(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    const glm::vec3 inward = glm::vec3(1.0f) - 2.0f * p; // toward the inside, per axis
    for (int a = 0; a < 3; ++a) {
      glm::vec3 n(0.0f);
      n[a] = inward[a];
      set.vpls.push_back(hand_vpl(p, n, VplKind::Surface)); // on each wall through the corner
    }
    set.vpls.push_back(hand_vpl(p, inward, VplKind::Surface));  // along the diagonal
    set.vpls.push_back(hand_vpl(p, inward, VplKind::TwoSided)); // both sides
    set.vpls.push_back(hand_vpl(p, inward, VplKind::Point));    // unclamped
  }
  // Edge midpoints, with either wall's normal.
  for (int axis = 0; axis < 3; ++axis)
    for (int c = 0; c < 4; ++c) {
      const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
      glm::vec3 p(0.5f);
      p[a1] = float(c & 1);
      p[a2] = float((c >> 1) & 1);
      glm::vec3 n1(0.0f), n2(0.0f);
      n1[a1] = 1.0f - 2.0f * p[a1];
      n2[a2] = 1.0f - 2.0f * p[a2];
      set.vpls.push_back(hand_vpl(p, n1, VplKind::Surface));
      set.vpls.push_back(hand_vpl(p, n2, VplKind::Surface));
    }
  // Just off an edge and a corner (1e-7 .. 1e-2 of the box), facing into the box: there the
  // receivers on the other wall are at distance ~eps with both cosines > 0, the weak singularity.
  for (float eps : {1e-7f, 1e-4f, 1e-2f}) {
    set.vpls.push_back(hand_vpl({eps, 0.0f, 0.5f}, {0, 1, 0}, VplKind::Surface)); // floor
    set.vpls.push_back(hand_vpl({0.0f, eps, 0.5f}, {1, 0, 0}, VplKind::Surface)); // wall x = 0
    set.vpls.push_back(hand_vpl({eps, eps, eps}, {1, 1, 1}, VplKind::Surface));
    set.vpls.push_back(hand_vpl({eps, eps, eps}, {1, 1, 1}, VplKind::Point));
  }
  // Wall centres.
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      glm::vec3 p(0.5f), n(0.0f);
      p[axis] = float(side);
      n[axis] = side ? -1.0f : 1.0f;
      set.vpls.push_back(hand_vpl(p, n, VplKind::Surface));
    }
  return set;
}

TEST(HardCases, VplsInCornersAndOnEdgesStayFinite) {
  const Scene s = closed_box(1.0f, 0.5f, 0.3f, 1.0f);
  const RayScene rays(s);
  const VplSet set = corner_vpls();
  EXPECT_EQ(set.vpls.size(), 8u * 6 + 12 * 2 + 3 * 4 + 6);
  // Odd sizes put the centre pixel's ray exactly on the corner (0,0,0), resp. on the edge
  // x = y = 0, and pixel centres on the edges along the image's axes.
  const Camera corner = look_at({0.8f, 0.8f, 0.8f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 1.2f);
  const Camera edge = look_at({0.8f, 0.8f, 0.5f}, {0.0f, 0.0f, 0.5f}, {0, 1, 0}, 1.6f);
  for (float clamp : {0.05f, 0.0f})
    for (const Camera* camera : {&corner, &edge}) {
      const View view = make_view(*camera, s.bounds, 33, 33);
      const Image traced = trace_vpls(s, rays, view, set, {clamp, 0});
      EXPECT_EQ(traced.non_finite_count(), 0u) << clamp;
      for (const glm::vec4& p : traced.pixels()) ASSERT_GE(std::min({p.r, p.g, p.b}), 0.0f);
      for (int k : interleaves) {
        RasterRenderer raster(s, raster_options(128, clamp, k));
        const Image image = raster.render(view, set);
        std::printf("corner VPLs, %s view, clamp %.2f, interleave %d: raster non-finite %zu max "
                    "%.4g; rt-vpl non-finite %zu max %.4g\n",
                    camera == &corner ? "corner" : "edge", clamp, k, image.non_finite_count(),
                    max_red(image), traced.non_finite_count(), max_red(traced));
        // Measured: no non-finite pixel; maxima 3.06e4 (interleave 1) and 7.2e4 (4) in the
        // corner view (the unclamped point light 1e-4 from the corner, seen by the centre
        // pixel), ~5 and 0.09 in the edge view.
        EXPECT_EQ(image.non_finite_count(), 0u) << clamp << " " << k;
        for (const glm::vec4& p : image.pixels()) ASSERT_GE(std::min({p.r, p.g, p.b}), 0.0f);
      }
    }
}

// One renderer serves several views and sizes in turn, as fresh renderers would (a depth buffer
// left from the previous render, or a new uninitialised one, must not leak into the next).
TEST(HardCases, RasterRendererServesAnotherViewAndSize) {
  Log log = quiet_log();
  const Scene s = closed_box(1.0f, 0.5f, 0.3f, 1.0f);
  const RayScene rays(s);
  const VplSet set = quasi_random_walk(s, rays, {64, 64}, log);
  const Camera a = look_at({0.8f, 0.8f, 0.8f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 1.2f);
  const Camera b = look_at({0.8f, 0.8f, 0.5f}, {0.0f, 0.0f, 0.5f}, {0, 1, 0}, 1.6f);
  const std::array<std::pair<const Camera*, int>, 4> views = {
      {{&a, 33}, {&b, 33}, {&a, 64}, {&a, 33}}};
  for (int k : interleaves) {
    std::vector<Image> expected;
    for (const auto& [camera, size] : views) {
      RasterRenderer fresh(s, raster_options(128, 0.05f, k));
      expected.push_back(fresh.render(make_view(*camera, s.bounds, size, size), set));
    }
    RasterRenderer reused(s, raster_options(128, 0.05f, k));
    for (std::size_t i = 0; i < views.size(); ++i) {
      const auto& [camera, size] = views[i];
      const Image image = reused.render(make_view(*camera, s.bounds, size, size), set);
      const ImageMetrics m = compare_images(image, expected[i]);
      std::printf("reused renderer, interleave %d, view %zu (%dx%d): mean ratio %.7f, relMSE "
                  "%.3g\n",
                  k, i, size, size, m.mean_ratio[0], m.relmse);
      // GL is deterministic here: the very same pixels.
      EXPECT_TRUE(image.pixels() == expected[i].pixels()) << k << " " << i;
    }
  }
}

// render() makes its renderer's GL context current: a renderer that made it current only at its
// construction would, once a second renderer exists, draw into the other (or a destroyed)
// context: an all-black image.
TEST(HardCases, TwoRasterRenderersInTurn) {
  Log log = quiet_log();
  const Scene s = closed_box(1.0f, 0.5f, 0.3f, 1.0f);
  const RayScene rays(s);
  const VplSet set = quasi_random_walk(s, rays, {64, 64}, log);
  const View view =
      make_view(look_at({0.8f, 0.8f, 0.8f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 1.2f), s.bounds, 33, 33);
  RasterRenderer first(s, raster_options(128, 0.05f, 1));
  const Image before = first.render(view, set);
  Image other;
  {
    RasterRenderer second(s, raster_options(64, 0.05f, 1));
    other = second.render(view, set);
  }
  const Image after = first.render(view, set);
  const ImageMetrics m = compare_images(after, before);
  std::printf("two renderers in turn: mean ratio %.7f, relMSE %.3g\n", m.mean_ratio[0], m.relmse);
  EXPECT_TRUE(after.pixels() == before.pixels());
  EXPECT_GT(mean_rgb(other), 0.0);
}

// A ray aimed exactly at a corner of a closed box meets a triangle: walk/rays/ray_scene.cpp builds
// the Embree scene with RTC_SCENE_FLAG_ROBUST. Without it such a ray misses every triangle (the
// rt-vpl pixel through the corner (0,0,0) of closed_box from (0.8,0.8,0.8) is 0 while the raster
// shows 3.06e4; 27 of 4000 rays escape).
TEST(HardCases, RaysFromInsideAClosedBoxNeverEscape) {
  const Scene s = closed_box(1.0f, 0.5f, 0.3f, 1.0f);
  const RayScene rays(s);
  std::vector<glm::vec3> targets; // the 8 corners and the 12 edge midpoints
  for (int c = 0; c < 8; ++c) targets.emplace_back(c & 1, (c >> 1) & 1, (c >> 2) & 1);
  for (int axis = 0; axis < 3; ++axis)
    for (int c = 0; c < 4; ++c) {
      glm::vec3 p(0.5f);
      p[(axis + 1) % 3] = float(c & 1);
      p[(axis + 2) % 3] = float((c >> 1) & 1);
      targets.push_back(p);
    }
  int misses = 0, total = 0;
  for (std::uint32_t i = 1; i <= 200; ++i) {
    const glm::vec3 origin(0.1f + 0.8f * float(radical_inverse(2, i)),
                           0.1f + 0.8f * float(radical_inverse(3, i)),
                           0.1f + 0.8f * float(radical_inverse(5, i)));
    for (const glm::vec3& t : targets) {
      ++total;
      if (!rays.intersect(origin, glm::normalize(t - origin), 0.0f, 10.0f)) ++misses;
    }
  }
  std::printf("rays at a closed box's corners and edges: %d of %d miss\n", misses, total);
  EXPECT_EQ(misses, 0);
}

} // namespace IRAD_UNITY_ID
} // namespace irad
