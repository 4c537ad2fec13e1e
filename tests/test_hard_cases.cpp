// Hard cases of the estimators: degenerate albedos (rho_bar = 0 and 1), extreme path counts, the
// scene's scale, a thin wall between a lit and a dark room, VPLs in corners, and the float
// accumulation of many passes. Every bound below is a measured value with a stated margin.
#include "core/gltf/loader.h"
#include "core/image_metrics.h"
#include "core/light_sampler.h"
#include "core/particle_counts.h"
#include "core/radical_inverse.h"
#include "core/scene_builder.h"
#include "core/view.h"
#include "raster/context/gl_context.h"
#include "raster/context/shader_program.h"
#include "raster/image/target.h"
#include "raster/raster_renderer.h"
#include "tests/test_rooms.h"
#include "walk/path_tracer.h"
#include "walk/quasi_random_walk.h"
#include "walk/thin_walls.h"
#include "walk/vpl_tracer.h"

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
namespace {

constexpr double pi = std::numbers::pi;

Log quiet_log() {
  return Log([](const std::string&) {});
}

// The raster with explicit settings; interleave 1 is the reference (every VPL shades every
// pixel), 4 the default (interleaved sampling and a geometry-aware resolve).
RasterOptions raster_options(int shadow_resolution, float clamp, int interleave) {
  RasterOptions o;
  o.shadow_resolution = shadow_resolution;
  o.clamp = clamp;
  o.interleave = interleave;
  return o;
}
constexpr int interleaves[] = {1, 4};

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

using test_support::add_room;
using test_support::two_rooms;
using test_support::TwoRooms;
const char* const room_wall_names[6] = {"floor",    "ceiling",   "wall z=0",
                                        "wall z=2", "wall x=lo", "wall x=hi"};

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
// 5. Two closed rooms side by side, 2 m each, separated by a 2 mm double wall; the light is in
// room A (x in [0, 2]) only, the camera in room B (x in [2.002, 4.002]) looks at the shared wall,
// its floor, ceiling and side walls. No light may reach B.

// Where light shows in an image of room B: in all and per wall of B, the number of non-zero
// pixels, the largest value (max over R, G, B) and the largest distance of such a pixel's surface
// point (the pixel-centre ray's hit) from the shared wall x = 2.002 (in the unscaled scene's
// metres: the scene is two_rooms(k)).
struct Leak {
  std::size_t pixels = 0;
  double max = 0.0, sum = 0.0, reach = 0.0;
  std::array<std::size_t, 6> wall_pixels{};
  std::array<double, 6> wall_max{}, wall_reach{};
};

Leak measure_leak(const Image& image, const RayScene& rays, const View& view, float k = 1.0f,
                  float wall_b = 2.002f) {
  Leak leak;
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const glm::vec4& p = image.at(x, y);
      const double v = std::max({p.r, p.g, p.b});
      if (v == 0.0) continue;
      ++leak.pixels;
      leak.max = std::max(leak.max, v);
      leak.sum += v;
      const CameraRay ray = pixel_ray(view, x, y);
      const glm::vec3 dir = ray.direction;
      const auto hit = rays.intersect(ray.origin, dir, 0.0f, 2.0f * view.zfar);
      const std::size_t quad = hit ? hit->triangle / 2 : 0;
      if (quad < 6 || quad >= 12) { // not a wall of room B: count it as far as can be
        leak.reach = HUGE_VAL;
        continue;
      }
      const std::size_t w = quad - 6;
      const double reach = double((ray.origin + hit->t * dir).x) / k - wall_b;
      leak.reach = std::max(leak.reach, reach);
      ++leak.wall_pixels[w];
      leak.wall_max[w] = std::max(leak.wall_max[w], v);
      leak.wall_reach[w] = std::max(leak.wall_reach[w], reach);
    }
  return leak;
}

void print_leak(const char* estimator, const Leak& leak, double reference) {
  std::printf("two rooms, %s: %zu lit pixels in room B, max %.3g (%.3g x room A's mean %.3g), "
              "sum %.3g, up to %.3f m from the shared wall\n",
              estimator, leak.pixels, leak.max, leak.max / reference, reference, leak.sum,
              leak.reach);
  for (int w = 0; w < 6; ++w)
    if (leak.wall_pixels[w] > 0)
      std::printf("  %-10s %4zu pixels, max %.3g, up to %.4f m from the shared wall\n",
                  room_wall_names[w], leak.wall_pixels[w], leak.wall_max[w], leak.wall_reach[w]);
}

struct TwoRoomImages {
  double room_a = 0.0; // mean radiance of a view of room A (rt-vpl), for scale
  Leak traced, pt;
  std::array<Leak, std::size(interleaves)> raster; // per interleave
  std::array<std::size_t, std::size(interleaves)> raster_nonfinite{};
};

TwoRoomImages render_two_rooms() {
  Log log = quiet_log();
  const TwoRooms rooms = two_rooms();
  const Scene& s = rooms.scene;
  const RayScene rays(s);
  const VplSet set = quasi_random_walk(s, rays, {128, 64}, log);
  for (const Vpl& v : set.vpls) EXPECT_LE(v.position.x, 2.0f); // every VPL is in room A
  const View view_b = make_view(rooms.in_b, s.bounds, 64, 64);
  const View view_a = make_view(rooms.in_a, s.bounds, 32, 32);
  TwoRoomImages r;
  r.room_a = mean_rgb(trace_vpls(s, rays, view_a, set, {0.05f, 0}));
  r.traced = measure_leak(trace_vpls(s, rays, view_b, set, {0.05f, 0}), rays, view_b);
  r.pt = measure_leak(path_trace(s, rays, view_b, {16, 1, 0, 1000}), rays, view_b);
  print_leak("rt-vpl", r.traced, r.room_a);
  print_leak("pt", r.pt, r.room_a);
  for (std::size_t i = 0; i < std::size(interleaves); ++i) {
    RasterRenderer raster(s, raster_options(256, 0.05f, interleaves[i]));
    const Image image = raster.render(view_b, set);
    r.raster_nonfinite[i] = image.non_finite_count();
    r.raster[i] = measure_leak(image, rays, view_b);
    print_leak(interleaves[i] == 1 ? "raster" : "raster (interleave 4)", r.raster[i], r.room_a);
  }
  return r;
}

TEST(HardCases, NoLightLeaksThroughATwoMillimetreWall) {
  const TwoRoomImages r = render_two_rooms();
  EXPECT_GT(r.room_a, 0.05); // measured 0.158: room A is lit
  // Exact visibility: not one pixel of room B receives light.
  EXPECT_EQ(r.traced.pixels, 0u);
  EXPECT_EQ(r.pt.pixels, 0u);
  // The raster's seams (see RasterShadowsHoldAtATwoMillimetreWall below). Measured (llvmpipe,
  // 256^2 faces, 64x64 pixels) with the occluder planes of raster/glsl/cube_glsl.h: interleave
  // 1: 4 of 4096 pixels, max 0.004 (0.025 x room A's mean), within 2 mm of the wall; interleave
  // 4: none (before the planes 265 and 488 pixels, up to 0.149 and 0.312 m from the wall).
  const std::size_t max_pixels[] = {10, 10};
  const double max_value[] = {0.01, 0.01}, max_reach[] = {0.005, 0.005};
  for (std::size_t i = 0; i < std::size(interleaves); ++i) {
    EXPECT_EQ(r.raster_nonfinite[i], 0u);
    EXPECT_LT(r.raster[i].pixels, max_pixels[i]) << interleaves[i];
    EXPECT_LT(r.raster[i].max, max_value[i]) << interleaves[i];
    EXPECT_LT(r.raster[i].reach, max_reach[i]) << interleaves[i];
  }
}

// The receiver-slope term of the former shadow bias, dist * texel * (1 + min(tan_x, 8)) with
// texel = 2/256, was up to 0.07 m at 1 m from the VPL: far thicker than the wall, so B's surfaces
// near the wall passed the shadow test (265 lit pixels, up to 0.149 m from the wall). The
// normal-offset lookup (raster/glsl/shaders.h) moves the receiver by dist * texel * sin_x along its
// normal and keeps only the constant bias. Measured: 4 seam pixels within 2 mm of the wall
// (max 0.021) at 256^2; this bound asks for that: light in B only at the seams.
TEST(HardCases, RasterShadowsHoldAtATwoMillimetreWall) {
  const TwoRoomImages r = render_two_rooms();
  EXPECT_LT(r.raster[0].reach, 0.005);
  EXPECT_LT(r.raster[0].pixels, 10u);
}

// The leak as `irad render` makes it by default (RasterOptions{}: batch 16, interleave 4, shadow
// faces of a quarter of the image side, 64 here, shadow LOD and occlusion on), with --batch 1 and
// with --interleave 1, at 1x, 10x and 0.1x the scene's size, as the ratio of the mean radiance of
// room B's image to that of room A's (the same mode and VPLs).
struct ModeLeak {
  const char* name;
  RasterOptions options;
  std::array<double, 3> ratio{}; // per scale
};

TEST(HardCases, TwoMillimetreWallLeaksTheSameInEveryModeAtAnyScale) {
  Log log = quiet_log();
  const float scales[3] = {1.0f, 10.0f, 0.1f};
  std::array<ModeLeak, 4> modes{{{"default", {}, {}},
                                 {"--batch 1", {}, {}},
                                 {"--interleave 1", {}, {}},
                                 {"--shadow-planes off", {}, {}}}};
  modes[1].options.batch = 1;
  modes[2].options.interleave = 1;
  modes[3].options.shadow_lod.planes = ShadowPlanes::Off;
  for (std::size_t j = 0; j < std::size(scales); ++j) {
    const TwoRooms rooms = two_rooms(scales[j]);
    const Scene& s = rooms.scene;
    const RayScene rays(s);
    const VplSet set = quasi_random_walk(s, rays, {128, 64}, log);
    const View view_b = make_view(rooms.in_b, s.bounds, 64, 64);
    const View view_a = make_view(rooms.in_a, s.bounds, 32, 32);
    EXPECT_EQ(measure_leak(trace_vpls(s, rays, view_b, set, {0.05f, 0}), rays, view_b).pixels, 0u);
    for (ModeLeak& m : modes) {
      RasterRenderer raster(s, m.options);
      const Image b = raster.render(view_b, set);
      const double room_a = mean_rgb(raster.render(view_a, set));
      m.ratio[j] = mean_rgb(b) / room_a;
      const Leak leak = measure_leak(b, rays, view_b, scales[j]);
      std::printf("two rooms at %gx, %s: leak %.4g of room A's mean %.3g, %zu lit pixels, max "
                  "%.3g (%.3g x room A), up to %.3f m from the wall\n",
                  scales[j], m.name, m.ratio[j], room_a, leak.pixels, leak.max, leak.max / room_a,
                  leak.reach);
    }
  }
  // Measured (llvmpipe, 64^2 faces, N = 128): default and --batch 1 2.76e-5 (44 pixels, max
  // 0.0065 x room A's mean, up to 0.22 m from the wall: the resolve spreads it), --interleave 1
  // 6.75e-5 (26 pixels, max 0.029 x, up to 2 cm), at every scale; issue 14 asks for below 1e-4.
  // Before the occluder planes (raster/glsl/cube_glsl.h) 2.70e-4 and 3.39e-4: one distance per
  // texel, at its centre, while across the texel the distance of a wall seen at theta varies by
  // dist * (2 / R) * tan(theta), far more than 2 mm. `--shadow-planes off` gives 5.1e-3 (the
  // switch works; it is bounded from below): without the planes a lookup trusts the receiver's
  // own plane and neighbourhood (cube_glsl.h in_front_of_receiver), which carries light along
  // the floor under a wall this thin (2.70e-4 with the centre's distance alone); `auto` never
  // turns them off for it. Bounds ~1.5-1.8x the measurements.
  const double bound[] = {5e-5, 5e-5, 1e-4, 8e-3};
  EXPECT_GT(modes[3].ratio[0], 1.5e-4);
  for (std::size_t i = 0; i < modes.size(); ++i) {
    EXPECT_LT(modes[i].ratio[0], bound[i]) << modes[i].name;
    // Every tolerance is a fraction of the diagonal: measured within 1.1e-3 of 1x
    // (--interleave 1 at 0.1x; the others within 1e-6); bound ~10x.
    for (int j = 1; j < 3; ++j) {
      std::printf("%s: leak at %gx / at 1x = %.6f\n", modes[i].name, scales[j],
                  modes[i].ratio[j] / modes[i].ratio[0]);
      EXPECT_NEAR(modes[i].ratio[j] / modes[i].ratio[0], 1.0, 0.01) << modes[i].name << scales[j];
    }
  }
}

// Without the occluder planes a shadow lookup trusts the receiver's own plane (raster/glsl/
// cube_glsl.h in_front_of_receiver): a texel whose centre ray meets a surface nearer than the
// receiver leaves it lit when that surface lies on the receiver's plane within 3 texels'
// footprints of it. That lets light along a plane under a wall thinner than those footprints,
// which is why thinner walls get the planes (raster_renderer.h planes_needed, walls below
// 4/R of the diagonal). The rooms with a double wall 1.25x that reach, the planes off as `auto`
// chooses them, every mode that reads them, at R = 64 and 128.
TEST(HardCases, AWallJustPastThePlanesReachLeaksNothingWithoutThem) {
  Log log = quiet_log();
  for (const int resolution : {64, 128}) {
    // The gap as a fraction of the diagonal, which itself grows with the gap: two steps suffice.
    float gap = 0.0f;
    for (int i = 0; i < 3; ++i)
      gap = 1.25f * planes_reach(resolution) * std::sqrt((4.0f + gap) * (4.0f + gap) + 8.0f);
    const TwoRooms rooms = two_rooms(1.0f, gap);
    const Scene& s = rooms.scene;
    const RayScene rays(s);
    ASSERT_FALSE(planes_needed(thinnest_wall(s, rays, planes_reach(resolution)), resolution));
    const VplSet set = quasi_random_walk(s, rays, {128, 64}, log);
    const View view_b = make_view(rooms.in_b, s.bounds, 64, 64);
    const View view_a = make_view(rooms.in_a, s.bounds, 32, 32);
    for (const int batch : {16, 1}) {
      RasterOptions o;
      o.shadow_resolution = resolution;
      o.batch = batch;
      o.shadow_lod.planes = ShadowPlanes::Off;
      RasterRenderer raster(s, o);
      const Image b = raster.render(view_b, set);
      const double ratio = mean_rgb(b) / mean_rgb(raster.render(view_a, set));
      const Leak leak = measure_leak(b, rays, view_b, 1.0f, rooms.wall_b);
      std::printf("wall %.3f m, R = %d, batch %d: leak %.3g of room A's mean, %zu lit pixels, up "
                  "to %.3f m from the wall\n",
                  gap, resolution, batch, ratio, leak.pixels, leak.reach);
      // Measured: 0 (no lit pixel) in every case (1.02x the reach: 5.9e-7 at R = 128); with twice
      // the reach of in_front_of_receiver's plane crossing 1.7e-6 (37 pixels), with no limit on it
      // 4e-6 (1165 pixels). Issue 14 asks for below 1e-4.
      EXPECT_LT(ratio, 1e-6) << resolution << " batch " << batch;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// 6. VPLs exactly at a box's corners, on its edges and on its walls.

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

// Found while writing the test above: a RasterRenderer made its GL context current only when it
// was created, so once a second renderer had been created, the first one's render() drew into the
// other (or a destroyed) context: an all-black image. render() now makes its context current.
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

// Found while writing the corner test: a ray aimed exactly at a corner of a closed box missed
// every triangle (the rt-vpl pixel through the corner (0,0,0) of closed_box from (0.8,0.8,0.8)
// was 0 while the raster showed 3.06e4; 27 of 4000 rays escaped), because the Embree scene was
// built without RTC_SCENE_FLAG_ROBUST. walk/ray_scene.cpp now sets it.
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

} // namespace
} // namespace irad
