// A thin wall between a lit and a dark room (tests/test_rooms.h two_rooms): exact visibility lets
// nothing through, the raster's shadow maps only at the seams, in every mode and at any scale;
// walls just thick enough to go without the occluder planes let nothing through either. Every
// bound is a measured value with a margin.
#include "core/camera/view.h"
#include "core/image/image_metrics.h"
#include "raster/raster_renderer.h"
#include "tests/raster_test_options.h"
#include "tests/test_rooms.h"
#include "walk/estimators/path_tracer.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/vpls/quasi_random_walk.h"
#include "walk/walls/thin_walls.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <string>

namespace irad {
namespace IRAD_UNITY_ID {

Log quiet_log() {
  return Log([](const std::string&) {});
}

using test_support::interleaves;
using test_support::raster_options;

double mean_rgb(const Image& image) {
  double sum = 0.0;
  for (const glm::vec4& p : image.pixels()) sum += double(p.r) + p.g + p.b;
  return sum / (3.0 * static_cast<double>(image.pixels().size()));
}

using test_support::two_rooms;
using test_support::TwoRooms;
const char* const room_wall_names[6] = {"floor",    "ceiling",   "wall z=0",
                                        "wall z=2", "wall x=lo", "wall x=hi"};

// Two closed rooms side by side, 2 m each, separated by a 2 mm double wall; the light is in
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
  // 256^2 faces, 64x64 pixels) with the occluder planes of raster/glsl/cube_glsl.h and their
  // concave corners: no pixel at interleave 1 or 4 (without the corners, interleave 1 keeps 4 of
  // 4096 pixels, max 0.004, within 2 mm of the wall).
  const std::size_t max_pixels[] = {10, 10};
  const double max_value[] = {0.01, 0.01}, max_reach[] = {0.005, 0.005};
  for (std::size_t i = 0; i < std::size(interleaves); ++i) {
    EXPECT_EQ(r.raster_nonfinite[i], 0u);
    EXPECT_LT(r.raster[i].pixels, max_pixels[i]) << interleaves[i];
    EXPECT_LT(r.raster[i].max, max_value[i]) << interleaves[i];
    EXPECT_LT(r.raster[i].reach, max_reach[i]) << interleaves[i];
  }
}

// The receiver-slope term of a slope-scaled shadow bias, dist * texel * (1 + min(tan_x, 8)) with
// texel = 2/256, is up to 0.07 m at 1 m from the VPL: far thicker than the wall, so B's surfaces
// near the wall would pass the shadow test (265 lit pixels, up to 0.149 m from the wall). The
// normal-offset lookup (raster/glsl/cube_glsl.h lookup_offset) moves the receiver by dist * texel *
// sin_x along its normal and keeps only the constant bias. Measured: 4 seam pixels within 2 mm of
// the wall (max 0.021) at 256^2; this bound asks for that: light in B only at the seams.
TEST(HardCases, RasterShadowsHoldAtATwoMillimetreWall) {
  const TwoRoomImages r = render_two_rooms();
  EXPECT_LT(r.raster[0].reach, 0.005);
  EXPECT_LT(r.raster[0].pixels, 10u);
}

// The leak as `irad render` makes it by default (RasterOptions{}: batch 64, interleave 4, shadow
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
  // Measured (llvmpipe, 64^2 faces, N = 128): default and --batch 1 4.07e-5 (53 pixels, max
  // 0.0082 x room A's mean, up to 0.22 m from the wall: the resolve spreads it), --interleave 1
  // 4.95e-5 (30 pixels, max 0.015 x, up to 2.4 cm), at every scale; the bound asked is 1e-4.
  // With k = 2 each pixel sees a quarter of the VPLs, 4x as bright: which of the few leaking
  // VPLs reach which pixels is the draw of the sets, and the expected leak is k = 1's (the sets
  // by a hash of the path, not core/lights/interleave_sets.h's blocks, draw 2.76e-5 in 44
  // pixels). With the centre's distance alone (no occluder planes, no receiver plane) 2.70e-4 and
  // 3.39e-4: one distance per texel, at its centre, while across the texel the distance of a
  // wall seen at theta varies by dist * (2 / R) * tan(theta), far more than 2 mm.
  // `--shadow-planes off` gives 5.1e-3 (the switch works; it is bounded from below): without the
  // planes a lookup trusts the receiver's own plane and neighbourhood (cube_glsl.h
  // in_front_of_receiver), which carries light along the floor under a wall this thin (2.70e-4
  // with the centre's distance alone); `auto` never turns them off for it. Bounds: the issue's
  // 1e-4 (1.5-1.7x the measurements), 8e-3.
  const double bound[] = {1e-4, 1e-4, 1e-4, 8e-3};
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
      // 4e-6 (1165 pixels). The bound asked is 1e-4.
      EXPECT_LT(ratio, 1e-6) << resolution << " batch " << batch;
    }
  }
}

} // namespace IRAD_UNITY_ID
} // namespace irad
