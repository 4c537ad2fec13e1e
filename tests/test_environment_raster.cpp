// The raster's background (raster/passes/background.h): pixels that see no surface show the distant
// environment's L(w) for the ray through the pixel centre (core/environment/environment.h, the same
// texel as Environment::radiance) and the disks of visible suns; `visible = false` shows nothing
// there and changes no lit pixel. The environment also lights the scene through directional VPLs
// (raster/passes/directional_pass.h).
//
// With IRAD_TEST_IMAGES=DIR the tests write their images to DIR.
#include "core/camera/view.h"
#include "core/environment/environment.h"
#include "core/image/image_io.h"
#include "core/scene/scene_builder.h"
#include "core/util/error.h"
#include "core/util/log.h"
#include "raster/raster_renderer.h"
#include "raster/ring_renderer.h"
#include "walk/rays/ray_scene.h"
#include "walk/vpls/quasi_random_walk.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <gtest/gtest.h>
#include <memory>
#include <numbers>
#include <string>

namespace irad {
namespace IRAD_UNITY_ID {

constexpr float pi = std::numbers::pi_v<float>;
constexpr int kSize = 64;

// Scaled by 1 / (the largest channel) for viewing: the index map's values run to 4096.
void maybe_write(const std::string& name, const Image& image) {
  const char* dir = std::getenv("IRAD_TEST_IMAGES");
  if (dir == nullptr) return;
  float top = 0.0f;
  for (const glm::vec4& p : image.pixels()) top = std::max({top, p.x, p.y, p.z});
  Image scaled = image;
  for (glm::vec4& p : scaled.pixels()) p = glm::vec4(glm::vec3(p) / std::max(top, 1e-30f), 1.0f);
  write_png(std::string(dir) + "/" + name + ".png", scaled);
}

// A 2h x h map whose texel (x, y) holds (x, y, x + 2h y + 1): every texel distinct.
Image index_map(int h = 32) {
  Image map(2 * h, h);
  for (int y = 0; y < map.height(); ++y)
    for (int x = 0; x < map.width(); ++x)
      map.at(x, y) = glm::vec4(float(x), float(y), float(x + map.width() * y + 1), 1.0f);
  return map;
}

// A small emitting square (radiance 1, double-sided) off to the right of a camera at the origin
// looking along -z, tilted up: most of the image is sky.
Scene small_object_scene(bool orthographic) {
  Scene s;
  const std::uint32_t m = add_material(s, glm::vec3(0.5f), glm::vec3(1.0f), true);
  add_quad(s, {0.6f, -0.2f, -2.0f}, {1.0f, -0.2f, -2.0f}, {1.0f, 0.2f, -2.0f}, {0.6f, 0.2f, -2.0f},
           m);
  Camera c = look_at({0.0f, 0.0f, 0.0f}, {0.3f, 0.4f, -1.0f}, {0, 1, 0}, 1.4f);
  if (orthographic) {
    c.orthographic = true;
    c.ymag = 1.0f;
  }
  s.cameras.push_back(c);
  finish(s);
  return s;
}

std::shared_ptr<Environment> index_environment(float rotation_degrees, int h = 32) {
  return std::make_shared<Environment>(index_map(h), 2.0f, rotation_degrees * pi / 180.0f,
                                       "index map");
}

Image render(const Scene& s, const View& view, int interleave, bool jitter = false,
             const VplSet& vpls = {}) {
  RasterOptions o;
  o.interleave = interleave;
  o.jitter = jitter;
  return RasterRenderer(s, o).render(view, vpls);
}

// The angle between world direction w and the nearest border of its map texel (column borders:
// the distance in phi times sin theta; row borders: the distance in theta), from the same
// map_coordinates the lookup uses.
double border_angle(const Environment& env, const glm::vec3& w) {
  const float c = std::cos(env.rotation()), s = std::sin(env.rotation());
  const glm::vec3 d(c * w.x - s * w.z, w.y, s * w.x + c * w.z);
  const glm::vec2 uv = Environment::map_coordinates(d);
  const double cw = double(uv.x) * env.map().width(), rh = double(uv.y) * env.map().height();
  const double du = std::abs(cw - std::round(cw)) / env.map().width() * 2.0 * std::numbers::pi;
  const double dv = std::abs(rh - std::round(rh)) / env.map().height() * std::numbers::pi;
  return std::min(du * std::sin(double(uv.y) * std::numbers::pi), dv);
}

bool same(const glm::vec4& a, const glm::vec4& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

struct BackgroundCheck {
  int background = 0; // pixels that see no surface
  int skipped = 0;    // of those, rays within `margin` of a texel border
  int mismatched = 0;
};

// Every background pixel of `image` (those black in `hidden`, the same scene with visible =
// false) against env.radiance(pixel_ray), skipping rays within `margin` radians of a border.
BackgroundCheck check_background(const Image& image, const Image& hidden, const View& view,
                                 const Environment& env, double margin) {
  BackgroundCheck r;
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      if (!same(hidden.at(x, y), glm::vec4(0.0f))) continue;
      ++r.background;
      const glm::vec3 w = pixel_ray(view, x, y).direction;
      if (border_angle(env, w) < margin) {
        ++r.skipped;
        continue;
      }
      if (!same(image.at(x, y), glm::vec4(env.radiance(w), 0.0f))) {
        if (r.mismatched++ < 5)
          ADD_FAILURE() << "pixel (" << x << ", " << y << "): " << image.at(x, y).z << " against "
                        << env.radiance(w).z << ", border angle " << border_angle(env, w);
      }
    }
  return r;
}

// Perspective and orthographic, interleave 1 and 4, no jitter: the background is the map's
// radiance exactly, except within 1e-5 rad of a texel border, where the GPU's atan may round
// differently (on llvmpipe none does: 0 mismatches with no pixel skipped; 1 of 4040 is skipped).
void expect_exact_background(bool orthographic, const std::string& name) {
  Scene s = small_object_scene(orthographic);
  const View view = make_view(s.cameras.at(0), s.bounds, kSize, kSize);
  auto env = index_environment(30.0f);
  s.environment = env;
  for (int interleave : {1, 4}) {
    env->visible = false;
    const Image hidden = render(s, view, interleave);
    env->visible = true;
    const Image shown = render(s, view, interleave);
    maybe_write(name + "_k" + std::to_string(interleave), shown);
    const BackgroundCheck r = check_background(shown, hidden, view, *env, 1e-5);
    std::printf("%s interleave %d: %d background pixels, %d skipped near texel borders\n",
                name.c_str(), interleave, r.background, r.skipped);
    EXPECT_GT(r.background, kSize * kSize / 2);
    EXPECT_LT(r.background, kSize * kSize);
    EXPECT_EQ(r.mismatched, 0);
    EXPECT_LT(r.skipped, r.background / 20);
  }
}

TEST(EnvironmentRaster, BackgroundEqualsMapRadianceExactly) {
  expect_exact_background(false, "env_background");
}

TEST(EnvironmentRaster, OrthographicBackgroundIsTheForwardTexel) {
  expect_exact_background(true, "env_background_ortho");
}

// With jitter the background is averaged over the emitters' 16 offsets: away from texel borders
// (1.5 pixel angles) every offset sees the same texel, and the average is that texel exactly
// (the values are small integers: 16 adds of v / 16 round nowhere). An 8 x 4 map: texels of
// 45 degrees, so that most pixels are away from their borders.
TEST(EnvironmentRaster, JitteredBackgroundAveragesWithinThePixel) {
  Scene s = small_object_scene(false);
  const View view = make_view(s.cameras.at(0), s.bounds, kSize, kSize);
  auto env = index_environment(30.0f, 4);
  s.environment = env;
  env->visible = false;
  const Image hidden = render(s, view, 1, true);
  env->visible = true;
  const Image shown = render(s, view, 1, true);
  maybe_write("env_background_jitter", shown);
  const double pixel_angle = 2.0 * std::tan(1.4 / 2.0) / kSize;
  const BackgroundCheck r = check_background(shown, hidden, view, *env, 1.5 * pixel_angle);
  std::printf("jitter: %d background pixels, %d skipped near texel borders\n", r.background,
              r.skipped);
  EXPECT_GT(r.background - r.skipped, kSize * kSize / 4);
  EXPECT_EQ(r.mismatched, 0);
}

// A sun of angular radius 0.1 rad (no environment: its disk on black). The pixels inside the disk
// are those whose ray has dot(w, -direction) >= cos r (within 1e-6 of the edge skipped), with
// radiance E / (pi sin^2 r).
TEST(EnvironmentRaster, SunDiskPixelsAndRadiance) {
  Scene s = small_object_scene(false);
  PunctualLight sun;
  sun.kind = PunctualLight::Kind::Directional;
  sun.direction = -glm::normalize(glm::vec3(-0.1f, 0.5f, -1.0f));
  sun.intensity = {3.0f, 2.0f, 1.0f};
  sun.angular_radius = 0.1f;
  s.lights = {sun};
  const View view = make_view(s.cameras.at(0), s.bounds, kSize, kSize);
  const float sin_r = std::sin(sun.angular_radius), cos_r = std::cos(sun.angular_radius);
  const glm::vec3 disk = sun.intensity / (pi * sin_r * sin_r);
  for (int interleave : {1, 4}) {
    const Image image = render(s, view, interleave);
    maybe_write("env_sun_k" + std::to_string(interleave), image);
    int inside = 0, expected = 0, edge = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const float c = glm::dot(pixel_ray(view, x, y).direction, -sun.direction);
        const bool in_disk = same(image.at(x, y), glm::vec4(disk, 0.0f));
        inside += in_disk ? 1 : 0;
        if (std::abs(c - cos_r) < 1e-6f) {
          ++edge;
          continue;
        }
        expected += c >= cos_r ? 1 : 0;
        EXPECT_EQ(in_disk, c >= cos_r) << "pixel " << x << ", " << y;
        if (!in_disk && c < cos_r && image.at(x, y).x != 1.0f) {
          EXPECT_TRUE(same(image.at(x, y), glm::vec4(0.0f))) << "pixel " << x << ", " << y;
        }
      }
    // The disk's solid angle 2 pi (1 - cos r) over the solid angle of a pixel near the centre.
    const double pixel = 2.0 * std::tan(1.4 / 2.0) / kSize;
    std::printf("sun interleave %d: %d pixels in the disk (%d expected, %d at its edge skipped, "
                "%.0f from its solid angle)\n",
                interleave, inside, expected, edge,
                2.0 * std::numbers::pi * (1.0 - cos_r) / (pixel * pixel));
    EXPECT_GT(expected, 50);
    EXPECT_NEAR(inside, expected, edge);
  }
}

// A floor under the index map, lit by the environment's directional VPLs (the walk): with
// visible = false the background is 0 and every lit pixel is bitwise the same.
TEST(EnvironmentRaster, InvisibleEnvironmentLeavesLitPixelsUnchanged) {
  Scene s;
  const std::uint32_t floor = add_material(s, glm::vec3(0.6f));
  const std::uint32_t box = add_material(s, {0.7f, 0.5f, 0.3f});
  add_quad(s, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}, floor);
  add_quad(s, {-0.4f, 0.6f, 0.4f}, {0.4f, 0.6f, 0.4f}, {0.4f, 0.6f, -0.4f}, {-0.4f, 0.6f, -0.4f},
           box);
  s.cameras.push_back(look_at({0.0f, 1.6f, 3.5f}, {0.0f, 0.3f, 0.0f}, {0, 1, 0}, 1.0f));
  finish(s);
  auto env = index_environment(30.0f);
  s.environment = env;
  Log log([](const std::string&) {});
  const RayScene rays(s);
  const VplSet vpls = quasi_random_walk(s, rays, {64, 64}, log);
  std::size_t directional = 0;
  for (const Vpl& v : vpls.vpls) directional += v.kind == VplKind::Directional ? 1 : 0;
  EXPECT_GT(directional, 32u);
  const View view = make_view(s.cameras.at(0), s.bounds, kSize, kSize);
  for (int interleave : {1, 4}) {
    env->visible = true;
    const Image shown = render(s, view, interleave, false, vpls);
    env->visible = false;
    const Image hidden = render(s, view, interleave, false, vpls);
    maybe_write("env_lit_k" + std::to_string(interleave), shown);
    int lit = 0, background = 0, sky = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const CameraRay ray = pixel_ray(view, x, y);
        const bool miss = !rays.intersect(ray.origin, ray.direction, 0.0f, 1e30f);
        sky += miss ? 1 : 0;
        if (same(hidden.at(x, y), glm::vec4(0.0f))) {
          ++background;
          continue;
        }
        ++lit;
        EXPECT_TRUE(same(shown.at(x, y), hidden.at(x, y))) << "pixel " << x << ", " << y;
        EXPECT_FALSE(miss) << "pixel " << x << ", " << y; // no light where no surface is seen
      }
    std::printf("visible=false, interleave %d: %d lit pixels unchanged, %d black (%d rays miss)\n",
                interleave, lit, background, sky);
    EXPECT_GT(lit, kSize * kSize / 3);
    EXPECT_GT(sky, kSize * 4);
    EXPECT_GE(background, sky);
  }
}

// The walkthrough's ring shows the same background as the RasterRenderer.
TEST(EnvironmentRaster, RingFrameShowsTheBackground) {
  Scene s = small_object_scene(false);
  auto env = index_environment(30.0f);
  s.environment = env;
  const View view = make_view(s.cameras.at(0), s.bounds, kSize, kSize);
  RingOptions o;
  o.paths = 2;
  o.width = o.height = kSize;
  RingRenderer ring(s, o);
  const Image frame = ring.frame(view);
  RasterOptions ro;
  ro.interleave = 1;
  const Image raster = RasterRenderer(s, ro).render(view, {});
  int differ = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) differ += same(frame.at(x, y), raster.at(x, y)) ? 0 : 1;
  EXPECT_EQ(differ, 0);
}

// The largest map the loader takes, 16384 x 8192 (2 GiB as an Image, 1.5 GiB as the RGB32F
// texture in 3 bands, ~8 s on llvmpipe): every background pixel is its texel (rows of two bands
// seen), or it throws irad::Error naming the map where
// GL_MAX_TEXTURE_SIZE is smaller. Disabled (memory and time): run with
// --gtest_also_run_disabled_tests.
TEST(EnvironmentRaster, DISABLED_LargestMapUploads) {
  Scene s = small_object_scene(false);
  Image map(16384, 8192);
  for (int y = 0; y < map.height(); ++y) // the row index: rows of every band are checked
    for (int x = 0; x < map.width(); ++x)
      map.at(x, y) = glm::vec4(2.0f + float(y), 0.5f, 0.75f, 1.0f);
  auto env = std::make_shared<Environment>(std::move(map), 1.0f, 0.0f, "large map");
  s.environment = env;
  const View view = make_view(s.cameras.at(0), s.bounds, 16, 16);
  try {
    const Image image = render(s, view, 1);
    int checked = 0, rows_past_first_band = 0;
    for (int y = 0; y < view.height; ++y)
      for (int x = 0; x < view.width; ++x) {
        const glm::vec3 w = pixel_ray(view, x, y).direction;
        if (image.at(x, y).x == 1.0f || border_angle(*env, w) < 1e-5) continue; // the object
        EXPECT_TRUE(same(image.at(x, y), glm::vec4(env->radiance(w), 0.0f))) << x << ", " << y;
        ++checked;
        rows_past_first_band += env->radiance(w).x > 2.0f + 8192.0f / 3.0f ? 1 : 0;
      }
    EXPECT_GT(checked, 128);
    EXPECT_GT(rows_past_first_band, 16);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("large map"), std::string::npos) << e.what();
    std::printf("%s\n", e.what());
  }
}

} // namespace IRAD_UNITY_ID
} // namespace irad
