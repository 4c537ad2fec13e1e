// Perfect mirrors (seed section 5.1.2, core/scene/mirrors.h): the loader's thresholds, the mirror
// polygons, the path tracer's mirror against Lambert's formula, the VPL estimators (mirrored VPLs,
// the raster's pyramid clip and mirrored shadow cube, the ray-traced pass over visible mirrors)
// against it and against the path tracer, and diffuse scenes untouched by all of it.
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/gltf/writer.h"
#include "core/image/image_metrics.h"
#include "core/scene/mirrors.h"
#include "core/scene/scene_builder.h"
#include "keep_written_gltf.h"
#include "raster/raster_renderer.h"
#include "tests/test_paths.h"
#include "walk/estimators/mirror_pass.h"
#include "walk/estimators/path_tracer.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/vpls/quasi_random_walk.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <numbers>

namespace irad {
namespace IRAD_UNITY_ID {

namespace fs = std::filesystem;
const fs::path cornell = fs::path(IRAD_SOURCE_DIR) / "data/cornell_box.gltf";
const fs::path cornell_mirror = fs::path(IRAD_SOURCE_DIR) / "data/cornell_mirror.gltf";

Log quiet_log() {
  return Log([](const std::string&) {});
}

// A mirror over a floor: the floor [-1, 1]^2 at z = 0 (albedo 0.5, facing up), a square light of
// side 0.2 and radiance 10 at z = 0.5 facing up (albedo 0), a mirror [-1, 1]^2 at z = 1 facing
// down (R = 0.8). The light faces away from the floor: only light reflected by the mirror reaches
// it. Camera at z = 0.9 looking down at the floor.
constexpr float floor_albedo = 0.5f, reflectance = 0.8f, radiance = 10.0f;
Scene mirror_over_floor() {
  Scene s;
  const auto floor = add_material(s, glm::vec3(floor_albedo));
  const auto light = add_material(s, glm::vec3(0.0f), glm::vec3(radiance));
  const auto mirror = add_material(s, glm::vec3(reflectance));
  s.materials[mirror].specular = true;
  add_quad(s, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, floor);
  add_quad(s, {-0.1f, -0.1f, 0.5f}, {0.1f, -0.1f, 0.5f}, {0.1f, 0.1f, 0.5f}, {-0.1f, 0.1f, 0.5f},
           light);
  add_quad(s, {-1, -1, 1}, {-1, 1, 1}, {1, 1, 1}, {1, -1, 1}, mirror);
  s.cameras.push_back(look_at({0.0f, 0.0f, 0.9f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 1.5f));
  finish(s);
  return s;
}

// The floor's radiance at x: rho/pi R E, E from the light's image (z = 1.5, facing down) by
// Lambert's formula. Exact where the light does not shade the path: max(|x|, |y|) >= 0.35.
double analytic_floor(const glm::vec3& x) {
  const std::vector<glm::dvec3> image = {
      {-0.1, -0.1, 1.5}, {-0.1, 0.1, 1.5}, {0.1, 0.1, 1.5}, {0.1, -0.1, 1.5}};
  return floor_albedo / std::numbers::pi * reflectance *
         polygon_irradiance(image, glm::dvec3(x), {0, 0, 1}, radiance);
}

// Images of the estimate and the analytic answer over the floor pixels where it is exact (others
// 0 in both).
struct Compared {
  Image estimate, analytic;
};
Compared against_analytic(const Scene& s, const RayScene& rays, const View& view,
                          const Image& image) {
  Compared c{Image(view.width, view.height), Image(view.width, view.height)};
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const CameraRay ray = pixel_ray(view, x, y);
      const glm::vec3 dir = ray.direction;
      const auto hit = rays.intersect(ray.origin, dir, view.znear, 10.0f);
      if (!hit || s.triangle_material[hit->triangle] != 0) continue;
      const glm::vec3 p = ray.origin + hit->t * dir;
      if (glm::max(std::abs(p.x), std::abs(p.y)) < 0.35f) continue;
      c.estimate.at(x, y) = glm::vec4(glm::vec3(image.at(x, y).r), 1.0f);
      c.analytic.at(x, y) = glm::vec4(glm::vec3(static_cast<float>(analytic_floor(p))), 1.0f);
    }
  // Both divided by the analytic mean over those pixels, so that relMSE is a relative error
  // (its eps = 0.01 would otherwise dwarf these small radiances).
  double sum = 0.0;
  std::size_t n = 0;
  for (const glm::vec4& p : c.analytic.pixels())
    if (p.r > 0.0f) {
      sum += p.r;
      ++n;
    }
  const float scale = static_cast<float>(static_cast<double>(n) / sum);
  for (Image* i : {&c.estimate, &c.analytic})
    for (glm::vec4& p : i->pixels()) p = glm::vec4(glm::vec3(p) * scale, 1.0f);
  return c;
}

double mean_of(const Image& image) {
  double sum = 0.0;
  for (const glm::vec4& p : image.pixels()) sum += p.r;
  return sum / static_cast<double>(image.pixels().size());
}

TEST(Specular, LoaderThresholdsAndWriterRoundTrip) {
  Log log = quiet_log();
  const Scene s = load_gltf(cornell_mirror, log);
  std::size_t mirrors = 0;
  for (const Material& m : s.materials) mirrors += m.specular ? 1 : 0;
  EXPECT_EQ(mirrors, 1u);
  EXPECT_FALSE(load_gltf(cornell, log).has_specular());
  const fs::path out = fs::path(::testing::TempDir()) / "irad_mirror_roundtrip.gltf";
  write_gltf(s, out);
  test::keep_written_gltf(out, "mirror_roundtrip.gltf");
  const Scene back = load_gltf(out, log);
  for (std::size_t k = 0; k < s.materials.size(); ++k)
    EXPECT_EQ(back.materials[k].specular, s.materials[k].specular) << k;
  fs::remove(out);
}

TEST(Specular, MirrorPolygons) {
  const Scene s = mirror_over_floor();
  const auto mirrors = find_mirrors(s);
  ASSERT_EQ(mirrors.size(), 1u); // one planar quad: one polygon of two triangles
  EXPECT_EQ(mirrors[0].triangles.size(), 6u);
  EXPECT_TRUE(inside_polygon(mirrors[0], {0.3f, -0.9f, 1.0f}));
  EXPECT_FALSE(inside_polygon(mirrors[0], {1.1f, 0.0f, 1.0f}));
  // A VPL below the mirror, facing up, and its image.
  Vpl v;
  v.position = {0.2f, 0.0f, 0.4f};
  v.normal = {0.0f, 0.0f, 1.0f};
  v.intensity = glm::vec3(1.0f);
  const auto copy = mirrored_vpl(v, mirrors, 0);
  ASSERT_TRUE(copy);
  EXPECT_NEAR(copy->position.z, 1.6f, 1e-6f);
  EXPECT_NEAR(copy->normal.z, -1.0f, 1e-6f);
  EXPECT_NEAR(copy->intensity.x, reflectance, 1e-6f);
  EXPECT_TRUE(mirror_crossing(*copy, mirrors[0], {0.5f, 0.5f, 0.0f}));
  EXPECT_FALSE(mirror_crossing(*copy, mirrors[0], {0.5f, 0.5f, 1.5f})); // behind the mirror
  EXPECT_FALSE(mirror_crossing(*copy, mirrors[0], {5.0f, 0.0f, 0.0f})); // outside the polygon
  v.normal = {0.0f, 0.0f, -1.0f}; // facing away from the mirror: no copy
  EXPECT_FALSE(mirrored_vpl(v, mirrors, 0));
  // The measured Cornell box's left wall is not planar: two polygons.
  Log log = quiet_log();
  EXPECT_EQ(find_mirrors(load_gltf(cornell_mirror, log)).size(), 2u);
}

// The path tracer's mirror (its ground truth role) against Lambert's formula: max_depth 2 keeps
// exactly the paths floor -> mirror -> light.
TEST(Specular, PathTracerMirrorMatchesLambert) {
  const Scene s = mirror_over_floor();
  const RayScene rays(s);
  const View view = make_view(s.cameras[0], s.bounds, 48, 48);
  const Image pt = path_trace(s, rays, view, {4096, 5, 0, 2});
  const Compared c = against_analytic(s, rays, view, pt);
  const ImageMetrics m = compare_images(c.estimate, c.analytic, 8);
  std::printf("pt vs Lambert via the mirror: mean ratio %.4f, relMSE (8x8 blocks) %.2e\n",
              m.mean_ratio[0], m.relmse);
  // Measured: ratio 1.0120 (seeds 5..14: 1.012, 1.008, 1.005, 1.001, 0.989, 1.001, 0.995, 1.000,
  // 1.004, 1.008: mean 1.002, sigma 0.007), relMSE 1.05e-3. Without the mirror bounce the floor
  // is black (ratio 0), without R the ratio is 1.25.
  EXPECT_NEAR(m.mean_ratio[0], 1.0, 0.025);
  EXPECT_LT(m.relmse, 3e-3);
}

// Mirrored VPLs alone (depth 0: the light's VPLs and their images) against Lambert's formula, with
// exact visibility and with the raster's pyramid clip and mirrored shadow cube.
TEST(Specular, MirroredVplsMatchLambert) {
  const Scene s = mirror_over_floor();
  const RayScene rays(s);
  Log log = quiet_log();
  VplSet vpls = quasi_random_walk(s, rays, {1024, 64}, log);
  std::erase_if(vpls.vpls, [](const Vpl& v) { return v.depth > 0; });
  std::size_t mirrored = 0;
  for (const Vpl& v : vpls.vpls) mirrored += v.mirror >= 0 ? 1 : 0;
  EXPECT_EQ(mirrored * 2, vpls.vpls.size()); // every light VPL faces the mirror
  const View view = make_view(s.cameras[0], s.bounds, 48, 48);
  const Image rt = trace_vpls(s, rays, view, vpls, {0.05f, 0});
  RasterOptions ro;
  ro.interleave = 1;
  RasterRenderer raster(s, ro);
  const Image gl = raster.render(view, vpls);
  for (const auto& [name, image] : {std::pair{"rt-vpl", &rt}, std::pair{"raster", &gl}}) {
    const Compared c = against_analytic(s, rays, view, *image);
    const ImageMetrics m = compare_images(c.estimate, c.analytic);
    std::printf("%s mirrored VPLs vs Lambert: mean ratio %.4f, relMSE %.2e\n", name,
                m.mean_ratio[0], m.relmse);
    // Measured: rt-vpl ratio 1.0000, relMSE 2.1e-8; raster 0.9998, 5.3e-8. Without R the ratio
    // is 1.25, without the copies 0, with the normal not reflected 0.
    EXPECT_NEAR(m.mean_ratio[0], 1.0, 0.005) << name;
    EXPECT_LT(m.relmse, 1e-5) << name;
  }
}

// A point light through the mirror (which the path tracer cannot see: a delta light in a delta
// mirror): the floor of mirror_over_floor lit by a point light of intensity I at (0.3, 0, 0.5)
// instead of the square light, directly and by way of its image at z = 1.5:
//   L(x) = rho/pi I (cos_x / d^2 + R cos_x' / d'^2),
// against the depth-0 VPLs (the light and its mirrored copy, both exact) of rt-vpl and the raster.
TEST(Specular, PointLightThroughMirrorIsExact) {
  Scene s;
  const auto floor = add_material(s, glm::vec3(floor_albedo));
  const auto mirror = add_material(s, glm::vec3(reflectance));
  s.materials[mirror].specular = true;
  add_quad(s, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, floor);
  add_quad(s, {-1, -1, 1}, {-1, 1, 1}, {1, 1, 1}, {1, -1, 1}, mirror);
  const glm::vec3 light(0.3f, 0.0f, 0.5f), image(0.3f, 0.0f, 1.5f);
  PunctualLight point;
  point.position = light;
  point.intensity = glm::vec3(2.0f);
  s.lights.push_back(point);
  s.cameras.push_back(look_at({0.0f, 0.0f, 0.9f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 1.5f));
  finish(s);
  const RayScene rays(s);
  Log log = quiet_log();
  VplSet vpls = quasi_random_walk(s, rays, {64, 64}, log);
  std::erase_if(vpls.vpls, [](const Vpl& v) { return v.depth > 0; });
  const View view = make_view(s.cameras[0], s.bounds, 48, 48);
  RasterOptions ro;
  ro.interleave = 1;
  RasterRenderer raster(s, ro);
  const Image gl = raster.render(view, vpls);
  const Image rt = trace_vpls(s, rays, view, vpls, {0.05f, 0});
  double worst_rt = 0.0, worst_gl = 0.0;
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const CameraRay ray = pixel_ray(view, x, y);
      const glm::vec3 dir = ray.direction;
      const auto hit = rays.intersect(ray.origin, dir, view.znear, 10.0f);
      ASSERT_TRUE(hit);
      const glm::vec3 p = ray.origin + hit->t * dir;
      const auto term = [&](const glm::vec3& source, float r) {
        const glm::vec3 d = source - p;
        return r * d.z / glm::length(d) / glm::dot(d, d);
      };
      const double expected =
          floor_albedo / std::numbers::pi * 2.0 * (term(light, 1.0f) + term(image, reflectance));
      worst_rt = std::max(worst_rt, std::abs(rt.at(x, y).r / expected - 1.0));
      worst_gl = std::max(worst_gl, std::abs(gl.at(x, y).r / expected - 1.0));
    }
  std::printf("point light through the mirror: worst relative error rt-vpl %.2e, raster %.2e\n",
              worst_rt, worst_gl);
  // Measured: rt-vpl 1.8e-6 (float rounding), raster 5.3e-4 (shadow-map and rasterized
  // positions). Without the mirrored copy the worst error is 0.475.
  EXPECT_LT(worst_rt, 1e-4);
  EXPECT_LT(worst_gl, 2e-3);
}

// A small mirror and a black occluder between it and the light: the raster's pyramid clip (a
// lit patch bounded by the mirror's outline) and its mirrored shadow cube (the occluder's shadow
// in the reflected light, seen from the image as the occluder's reflection) against rt-vpl's
// exact visibility, on the same mirrored VPLs.
TEST(Specular, SmallMirrorAndOccluderRasterMatchesRtVpl) {
  const auto scene = [](bool occluder) {
    Scene s;
    const auto floor = add_material(s, glm::vec3(floor_albedo));
    const auto light = add_material(s, glm::vec3(0.0f), glm::vec3(radiance));
    const auto mirror = add_material(s, glm::vec3(reflectance));
    const auto black = add_material(s, glm::vec3(0.0f));
    s.materials[mirror].specular = true;
    add_quad(s, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, floor);
    add_quad(s, {-0.1f, -0.1f, 0.5f}, {0.1f, -0.1f, 0.5f}, {0.1f, 0.1f, 0.5f}, {-0.1f, 0.1f, 0.5f},
             light);
    add_quad(s, {-0.2f, 0.1f, 1}, {-0.2f, 0.5f, 1}, {0.3f, 0.5f, 1}, {0.3f, 0.1f, 1}, mirror);
    if (occluder)
      add_quad(s, {0.0f, 0.1f, 0.8f}, {0.0f, 0.25f, 0.8f}, {0.2f, 0.25f, 0.8f}, {0.2f, 0.1f, 0.8f},
               black);
    s.cameras.push_back(look_at({0.0f, 0.0f, 0.9f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 1.5f));
    finish(s);
    return s;
  };
  Log log = quiet_log();
  double lit[2] = {0.0, 0.0};
  for (const bool occluder : {false, true}) {
    const Scene s = scene(occluder);
    const RayScene rays(s);
    VplSet vpls = quasi_random_walk(s, rays, {256, 64}, log);
    std::erase_if(vpls.vpls, [](const Vpl& v) { return v.depth > 0; });
    const View view = make_view(s.cameras[0], s.bounds, 64, 64);
    const Image rt = trace_vpls(s, rays, view, vpls, {0.05f, 0});
    RasterOptions ro;
    ro.interleave = 1;
    RasterRenderer raster(s, ro);
    const Image gl = raster.render(view, vpls);
    // The floor only (the light's own pixels are L_e in both).
    Image a(64, 64), b(64, 64);
    std::size_t dark = 0, pixels = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const auto hit = rays.intersect(pixel_ray(view, x, y).origin,
                                        pixel_ray(view, x, y).direction, view.znear, 9.0f);
        if (!hit || s.triangle_material[hit->triangle] != 0) continue;
        a.at(x, y) = glm::vec4(glm::vec3(gl.at(x, y)) * 100.0f, 1.0f);
        b.at(x, y) = glm::vec4(glm::vec3(rt.at(x, y)) * 100.0f, 1.0f);
        ++pixels;
        dark += rt.at(x, y).r == 0.0f ? 1 : 0;
      }
    const ImageMetrics m = compare_images(a, b);
    lit[occluder ? 1 : 0] = mean_of(b);
    std::printf("occluder %d: raster vs rt-vpl (x100) mean ratio %.4f, relMSE %.2e, max abs %.3f;"
                " floor pixels dark in rt-vpl %zu of %zu\n",
                occluder, m.mean_ratio[0], m.relmse, m.max_abs_error, dark, pixels);
    // Measured: see docs/ext/specular.md.
    EXPECT_NEAR(m.mean_ratio[0], 1.0, 0.02) << occluder;
    EXPECT_LT(m.relmse, 2e-3) << occluder;
    EXPECT_GT(dark, pixels / 4); // the pyramid lights a patch of the floor, not all of it
  }
  EXPECT_LT(lit[1], 0.9 * lit[0]); // the occluder's shadow matters
}

// Which surfaces the primary ray through each pixel sees: 0 other, 1 mirror, 2 white floor,
// 3 green wall (facing the mirror).
std::vector<int> regions(const Scene& s, const RayScene& rays, const View& view) {
  std::vector<int> out(static_cast<std::size_t>(view.width * view.height), 0);
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const CameraRay ray = pixel_ray(view, x, y);
      const glm::vec3 dir = ray.direction;
      const auto hit = rays.intersect(ray.origin, dir, view.znear, 2.0f * view.zfar);
      if (!hit) continue;
      const glm::vec3 p = ray.origin + hit->t * dir;
      int r = 0;
      if (s.material_of(hit->triangle).specular)
        r = 1;
      else if (p.y < 1e-3f && s.material_of(hit->triangle).name == "white")
        r = 2;
      else if (s.material_of(hit->triangle).name == "green")
        r = 3;
      out[static_cast<std::size_t>(y * view.width + x)] = r;
    }
  return out;
}

glm::dvec3 region_mean(const Image& image, const std::vector<int>& region, int which) {
  glm::dvec3 sum(0.0);
  std::size_t n = 0;
  for (std::size_t i = 0; i < region.size(); ++i)
    if (region[i] == which) {
      sum += glm::dvec3(glm::vec3(image.pixels()[i]));
      ++n;
    }
  return n ? sum / static_cast<double>(n) : sum;
}

// The Cornell box with a mirror for its left wall: raster (with its ray-traced pass over the
// mirror) and rt-vpl against the path tracer, over the image, the mirror's pixels and the floor.
TEST(Specular, CornellMirrorMatchesPathTracer) {
  Log log = quiet_log();
  const Scene s = load_gltf(cornell_mirror, log);
  const RayScene rays(s);
  const View view = make_view(s.cameras.at(0), s.bounds, 48, 48);
  const VplSet vpls = quasi_random_walk(s, rays, {512, 64}, log);
  const Image pt = path_trace(s, rays, view, {2048, 1, 0, 1000});
  const Image rt = trace_vpls(s, rays, view, vpls, {0.05f, 0});
  RasterRenderer raster(s, RasterOptions{});
  Image gl = raster.render(view, vpls);
  add_mirror_pass(s, rays, view, vpls, {0.05f, 0}, gl);
  const std::vector<int> region = regions(s, rays, view);
  const glm::dvec3 pt_mirror = region_mean(pt, region, 1), pt_floor = region_mean(pt, region, 2),
                   pt_green = region_mean(pt, region, 3);
  for (const auto& [name, image] : {std::pair<const char*, const Image*>{"rt-vpl", &rt},
                                    std::pair<const char*, const Image*>{"raster", &gl}}) {
    const ImageMetrics m = compare_images(*image, pt, 8);
    const glm::dvec3 mirror = region_mean(*image, region, 1) / pt_mirror;
    const glm::dvec3 floor = region_mean(*image, region, 2) / pt_floor;
    const glm::dvec3 green = region_mean(*image, region, 3) / pt_green;
    std::printf("%s vs pt: relMSE (8x8 blocks) %.2e, mean ratio %.4f %.4f %.4f, mirror region "
                "%.4f %.4f %.4f, floor %.4f %.4f %.4f, green wall %.4f %.4f %.4f\n",
                name, m.relmse, m.mean_ratio[0], m.mean_ratio[1], m.mean_ratio[2], mirror.x,
                mirror.y, mirror.z, floor.x, floor.y, floor.z, green.x, green.y, green.z);
    // Measured (48x48, N = 512, 2048 spp): rt-vpl relMSE 1.24e-3, mean ratio 0.989 0.998 0.987,
    // mirror region 1.016 1.042 0.992, floor 0.963 0.979 0.963, green wall 0.970 0.984 0.972;
    // raster relMSE 1.08e-3, the same mirror region (it is ray traced), floor 0.973 0.992 0.973.
    // Both converge: at N = 4096 and 8192 spp rt-vpl has relMSE 2.6e-4, mirror region 0.999
    // 1.006 0.995, floor 0.977 (the clamp's loss in the block's shadow, as without the mirror).
    // Without the mirrored VPLs: relMSE 2.4e-2, floor 0.67, mirror region 0.62, green wall 0.88;
    // without the mirror pass the mirror region is 0.
    EXPECT_LT(m.relmse, 4e-3) << name;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(m.mean_ratio[c], 1.0, 0.04) << name << c;
      EXPECT_NEAR(mirror[c], 1.0, 0.07) << name << c;
      EXPECT_NEAR(floor[c], 1.0, 0.07) << name << c;
      EXPECT_NEAR(green[c], 1.0, 0.07) << name << c;
    }
  }
}

bool same_vpls(const VplSet& a, const VplSet& b) {
  if (a.vpls.size() != b.vpls.size()) return false;
  for (std::size_t k = 0; k < a.vpls.size(); ++k) {
    const Vpl &u = a.vpls[k], &v = b.vpls[k];
    if (u.position != v.position || u.normal != v.normal || u.intensity != v.intensity ||
        u.kind != v.kind || u.depth != v.depth || u.path != v.path || u.mirror != v.mirror)
      return false;
  }
  return true;
}

// A diffuse scene takes the diffuse code paths: no mirrored VPL, no mirror program in use, and
// the same bits whether or not the scene carries a (unused) specular material, which switches the
// mirror machinery on (the walk's mirror list, the raster's second program, the mirror pass).
TEST(Specular, DiffuseSceneUnchanged) {
  Log log = quiet_log();
  const Scene plain = load_gltf(cornell, log);
  Scene with_mirror_material = plain;
  Material mirror;
  mirror.name = "unused mirror";
  mirror.base_color = glm::vec3(0.9f);
  mirror.specular = true;
  with_mirror_material.materials.push_back(mirror);
  ASSERT_TRUE(with_mirror_material.has_specular());
  const RayScene rays_a(plain), rays_b(with_mirror_material);
  const VplSet a = quasi_random_walk(plain, rays_a, {64, 64}, log);
  const VplSet b = quasi_random_walk(with_mirror_material, rays_b, {64, 64}, log);
  EXPECT_TRUE(a.mirrors.empty());
  EXPECT_TRUE(same_vpls(a, b));
  for (const Vpl& v : a.vpls) EXPECT_LT(v.mirror, 0);
  const View view = make_view(plain.cameras.at(0), plain.bounds, 32, 32);
  RasterTimings ta, tb;
  RasterRenderer ra(plain, RasterOptions{}), rb(with_mirror_material, RasterOptions{});
  const Image ga = ra.render(view, a, &ta);
  Image gb = rb.render(view, b, &tb);
  add_mirror_pass(with_mirror_material, rays_b, view, b, {0.05f, 0}, gb);
  EXPECT_EQ(ta.passes, a.vpls.size()); // one pass per VPL: nothing extra
  EXPECT_EQ(ta.passes, tb.passes);
  EXPECT_EQ(ga.pixels(), gb.pixels());
  EXPECT_EQ(trace_vpls(plain, rays_a, view, a, {0.05f, 0}).pixels(),
            trace_vpls(with_mirror_material, rays_b, view, b, {0.05f, 0}).pixels());
  EXPECT_EQ(path_trace(plain, rays_a, view, {4, 1, 0, 1000}).pixels(),
            path_trace(with_mirror_material, rays_b, view, {4, 1, 0, 1000}).pixels());
}

// Jitter keeps the mirrors unlit by diffuse light: with interleaving the resolve multiplies by
// the albedo averaged over the jittered camera passes, and that average must zero the mirror's
// (as the G-buffer does); the light a mirror shows is the ray-traced mirror pass's.
TEST(Specular, JitterLeavesTheMirrorsUnlit) {
  Log log = quiet_log();
  const Scene s = load_gltf(cornell_mirror, log);
  const RayScene rays(s);
  const VplSet vpls = quasi_random_walk(s, rays, {64, 64}, log);
  const View view = make_view(s.cameras.at(0), s.bounds, 64, 64);
  RasterOptions options; // k = 4
  const Image off = RasterRenderer(s, options).render(view, vpls);
  options.jitter = true;
  const Image on = RasterRenderer(s, options).render(view, vpls);
  // The pixels inside a mirror: every sub-pixel ray of the pixel (4 x 4) hits a mirror.
  const auto inside_mirror = [&](int x, int y) {
    for (int j = 0; j < 16; ++j) {
      const CameraRay ray =
          image_point_ray(view, static_cast<float>(x) + (static_cast<float>(j % 4) + 0.5f) / 4.0f,
                          static_cast<float>(y) + (static_cast<float>(j / 4) + 0.5f) / 4.0f);
      const auto hit = rays.intersect(ray.origin, ray.direction, view.znear, 2.0f * view.zfar);
      if (!hit || !s.material_of(hit->triangle).specular) return false;
    }
    return true;
  };
  double mirror = 0.0, rest = 0.0;
  int mirror_pixels = 0, rest_pixels = 0;
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const glm::vec4 p = on.at(x, y);
      if (inside_mirror(x, y)) {
        mirror += p.r + p.g + p.b;
        ++mirror_pixels;
        EXPECT_EQ(off.at(x, y), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
      } else {
        rest += p.r + p.g + p.b;
        ++rest_pixels;
      }
    }
  ASSERT_GT(mirror_pixels, 200);
  const double inside = mirror / mirror_pixels, outside = rest / rest_pixels;
  std::printf("jitter on: mean inside the mirrors %.3g (%d pixels), elsewhere %.3g\n", inside,
              mirror_pixels, outside);
  // Measured: 6.4e-4 inside the mirrors, 1.4e-3 of the mean elsewhere (0 without jitter). With
  // the mirror's base colour in the averaged albedo: 0.474 against 0.454 (the mirrors lit like
  // walls, the CLI's image 14.6 % too bright after the mirror pass).
  EXPECT_LT(inside, 1e-2 * outside);
}

// The command line: a mirror scene renders with the mirror pass timed; the clamp's residual,
// which does not handle mirrors, is refused with one line, exit 1.
TEST(Specular, CommandLine) {
  const fs::path dir = fs::path(::testing::TempDir()) / "irad_specular_cli";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path panel = fs::path(IRAD_SOURCE_DIR) / "data/cornell_mirror_panel.gltf";
  const std::string render = std::string(IRAD_BINARY) + " render " + panel.string() + " -o " +
                             (dir / "p.exr").string() + " --size 32x32 --paths 16 --quiet";
  ASSERT_EQ(std::system((render + " --stats " + (dir / "s.json").string()).c_str()), 0);
  std::ifstream in(dir / "s.json");
  const nlohmann::json stats = nlohmann::json::parse(in);
  EXPECT_TRUE(stats["seconds"].contains("mirrors"));
  EXPECT_GT(stats["vpls"].get<int>(), stats["vpls_planned"].get<int>()); // the mirrored copies
  const int status =
      std::system((render + " --bias-compensation 2> " + (dir / "err.txt").string()).c_str());
  EXPECT_EQ(WEXITSTATUS(status), 1);
  std::ifstream err(dir / "err.txt");
  const std::string message((std::istreambuf_iterator<char>(err)), {});
  EXPECT_NE(message.find("does not handle mirrors"), std::string::npos) << message;
  fs::remove_all(dir);
}

} // namespace IRAD_UNITY_ID
} // namespace irad
