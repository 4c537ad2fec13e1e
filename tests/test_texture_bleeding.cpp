// Textures colour the bounced light (the seed's "a red wall bleeds"): a box whose left wall is a
// red | blue base-colour texture (white base colour factor). The walk reads the texture at each
// hit (core/scene/scene.cpp albedo_at), the raster samples the same texture: the floor next to the
// red half must turn red and the floor next to the blue half blue, in raster, rt-vpl and pt alike,
// and the two VPL estimators must match pt on the floor and on the wall.
#include "core/camera/view.h"
#include "core/image/image_metrics.h"
#include "core/scene/scene_builder.h"
#include "core/scene/texture.h"
#include "raster/raster_renderer.h"
#include "tests/doc_images.h"
#include "walk/estimators/path_tracer.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/rays/ray_scene.h"
#include "walk/vpls/quasi_random_walk.h"

#include <array>
#include <cstdio>
#include <gtest/gtest.h>

namespace irad {
namespace IRAD_UNITY_ID {

constexpr glm::vec3 kRed(0.8f, 0.05f, 0.05f), kBlue(0.05f, 0.05f, 0.8f);

// The box [0,1]^3 open at z = 1 (the camera looks in from there): floor, ceiling, back and right
// walls grey, the left wall x = 0 textured: u runs along z, the back half (z < 1/2) red, the
// front half blue (16 x 1 texels, clamped: the blend between the halves is 1/16 wide). A square
// light of side 0.3 just below the ceiling.
Scene textured_box() {
  Scene s;
  s.source = "textured_box";
  const std::uint32_t floor = add_material(s, glm::vec3(0.75f));
  const std::uint32_t grey = add_material(s, glm::vec3(0.6f));
  const std::uint32_t wall = add_material(s, glm::vec3(1.0f));
  const std::uint32_t light = add_material(s, glm::vec3(0.0f), glm::vec3(12.0f));
  add_quad(s, {0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}, floor);
  add_quad(s, {0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}, grey);
  add_quad(s, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, grey);
  add_quad(s, {1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0}, grey);
  const std::size_t first_wall_vertex = s.positions.size();
  add_quad(s, {0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}, wall);
  add_quad(s, {0.35f, 0.98f, 0.35f}, {0.65f, 0.98f, 0.35f}, {0.65f, 0.98f, 0.65f},
           {0.35f, 0.98f, 0.65f}, light);
  s.uvs.assign(s.positions.size(), glm::vec2(0.0f));
  const glm::vec2 wall_uv[4] = {{0, 1}, {0, 0}, {1, 0}, {1, 1}}; // u = z, v = 1 - y
  for (int k = 0; k < 4; ++k) s.uvs[first_wall_vertex + k] = wall_uv[k];
  Texture tex;
  tex.name = "red_blue";
  tex.width = 16;
  tex.height = 1;
  for (int i = 0; i < 16; ++i) tex.texels.push_back(glm::vec4(i < 8 ? kRed : kBlue, 1.0f));
  tex.wrap_s = tex.wrap_t = Wrap::ClampToEdge;
  s.textures.push_back(tex);
  s.materials[wall].base_color_texture = 0;
  s.cameras.push_back(look_at({0.5f, 0.5f, 2.4f}, {0.5f, 0.45f, 0.5f}, {0, 1, 0}, 0.75f));
  finish(s);
  return s;
}

// Regions of the visible surface, by the world point each pixel centre sees (ray cast).
enum Region { FloorRed, FloorBlue, WallRed, WallBlue, kRegions };

std::vector<int> regions(const RayScene& rays, const View& view) {
  std::vector<int> out(static_cast<std::size_t>(view.width * view.height), -1);
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const CameraRay ray = pixel_ray(view, x, y);
      const glm::vec3 d = ray.direction;
      const auto hit = rays.intersect(view.eye, d, 0.0f, 1e30f);
      if (!hit) continue;
      const glm::vec3 p = view.eye + hit->t * d;
      int r = -1;
      // The floor within 0.05..0.2 of the wall (closer, the clamp removes most of the bleeding),
      // away from the halves' border and from the back wall.
      if (p.y < 1e-3f && p.x > 0.05f && p.x < 0.2f) {
        if (p.z > 0.05f && p.z < 0.45f) r = FloorRed;
        if (p.z > 0.55f && p.z < 0.95f) r = FloorBlue;
      }
      if (p.x < 1e-3f && p.y > 0.1f && p.y < 0.9f) {
        if (p.z > 0.1f && p.z < 0.4f) r = WallRed;
        if (p.z > 0.6f && p.z < 0.9f) r = WallBlue;
      }
      out[static_cast<std::size_t>(y * view.width + x)] = r;
    }
  return out;
}

using RegionMeans = std::array<glm::dvec3, kRegions>;

RegionMeans region_means(const Image& image, const std::vector<int>& region) {
  RegionMeans sum{};
  std::array<int, kRegions> count{};
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const int r = region[static_cast<std::size_t>(y * image.width() + x)];
      if (r < 0) continue;
      sum[r] += glm::dvec3(glm::vec3(image.at(x, y)));
      ++count[r];
    }
  for (int r = 0; r < kRegions; ++r) {
    EXPECT_GT(count[r], 20) << "region " << r;
    sum[r] /= static_cast<double>(std::max(count[r], 1));
  }
  return sum;
}

void print(const char* name, const RegionMeans& m) {
  static const char* names[kRegions] = {"floor red", "floor blue", "wall red", "wall blue"};
  for (int r = 0; r < kRegions; ++r)
    std::printf("%-8s %-10s %.4f %.4f %.4f  r/b %.3f\n", name, names[r], m[r].r, m[r].g, m[r].b,
                m[r].r / m[r].b);
}

// Bleeding contrast: (R/B on the floor by the red half) / (R/B on the floor by the blue half).
double contrast(const RegionMeans& m) {
  return (m[FloorRed].r / m[FloorRed].b) / (m[FloorBlue].r / m[FloorBlue].b);
}

class TextureBleeding : public ::testing::Test {
protected:
  static constexpr int kSize = 64;
  static constexpr std::uint32_t kPaths = 256;
  static void SetUpTestSuite() {
    log_ = new Log([](const std::string&) {});
    scene_ = new Scene(textured_box());
    rays_ = new RayScene(*scene_);
    view_ = new View(make_view(scene_->cameras.at(0), scene_->bounds, kSize, kSize));
    region_ = new std::vector<int>(regions(*rays_, *view_));
    vpls_ = new VplSet(quasi_random_walk(*scene_, *rays_, {kPaths, 64}, *log_));
    PathTracerOptions pt;
    pt.spp = 512;
    reference_ = new Image(path_trace(*scene_, *rays_, *view_, pt));
  }
  static void TearDownTestSuite() {
    delete reference_;
    delete vpls_;
    delete region_;
    delete view_;
    delete rays_;
    delete scene_;
    delete log_;
  }
  static Image raster(const VplSet& vpls, int interleave = 4) {
    RasterOptions options;
    options.interleave = interleave;
    // pt sends its camera rays through pixel centres: the raster samples them too (no jitter),
    // so the two integrate the same function pixel by pixel, edges included.
    options.jitter = false;
    RasterRenderer r(*scene_, options);
    return r.render(*view_, vpls);
  }
  // Documentation pictures (only with IRAD_DOC_IMAGES), 4x nearest, side by side.
  static void picture(const char* name, std::initializer_list<const Image*> images) {
    if (doc_images::directory().empty()) return;
    std::vector<Image> big;
    for (const Image* i : images)
      big.push_back(doc_images::magnified_crop(*i, 0, 0, kSize, kSize, 4));
    if (big.size() == 2) doc_images::write(name, doc_images::side_by_side({&big[0], &big[1]}, 8));
    if (big.size() == 3)
      doc_images::write(name, doc_images::side_by_side({&big[0], &big[1], &big[2]}, 8));
  }
  static Image rt_vpl() { return trace_vpls(*scene_, *rays_, *view_, *vpls_, {}); }
  static inline Log* log_ = nullptr;
  static inline Scene* scene_ = nullptr;
  static inline RayScene* rays_ = nullptr;
  static inline View* view_ = nullptr;
  static inline std::vector<int>* region_ = nullptr;
  static inline VplSet* vpls_ = nullptr;
  static inline Image* reference_ = nullptr;
};

TEST_F(TextureBleeding, FloorTakesTheColourOfTheTextureHalfNextToIt) {
  const Image raster_image = raster(*vpls_), rt_image = rt_vpl();
  const RegionMeans pt = region_means(*reference_, *region_);
  const RegionMeans ra = region_means(raster_image, *region_);
  const RegionMeans rt = region_means(rt_image, *region_);
  picture("ext_texture_bleeding.png", {reference_, &raster_image, &rt_image});
  print("pt", pt);
  print("raster", ra);
  print("rt-vpl", rt);
  std::printf("contrast pt %.3f raster %.3f rt-vpl %.3f\n", contrast(pt), contrast(ra),
              contrast(rt));
  // The floor by the red half is redder than by the blue half: contrast measured pt 1.49, raster
  // 1.37, rt-vpl 1.43; a walk that ignores the texture gives 1.000 (the control below).
  for (const RegionMeans* m : {&pt, &ra, &rt}) {
    EXPECT_GT(contrast(*m), 1.25);
    EXPECT_GT((*m)[FloorRed].r / (*m)[FloorRed].b, 1.1);    // measured 1.20..1.24
    EXPECT_LT((*m)[FloorBlue].r / (*m)[FloorBlue].b, 0.95); // measured 0.83..0.87
  }
  // The VPL estimators keep pt's contrast within 10 % (measured raster -8 %, rt-vpl -4 %: the
  // clamp removes some of the near-wall bleeding).
  EXPECT_NEAR(contrast(ra) / contrast(pt), 1.0, 0.1);
  EXPECT_NEAR(contrast(rt) / contrast(pt), 1.0, 0.1);
}

TEST_F(TextureBleeding, VplEstimatorsMatchThePathTracer) {
  const Image ra = raster(*vpls_);
  const Image ra1 = raster(*vpls_, 1);
  const Image rt = rt_vpl();
  const RegionMeans pt = region_means(*reference_, *region_);
  for (const auto& [name, image] : {std::pair<const char*, const Image*>{"raster", &ra},
                                    {"raster k1", &ra1},
                                    {"rt-vpl", &rt}}) {
    const RegionMeans m = region_means(*image, *region_);
    for (int r = 0; r < kRegions; ++r)
      std::printf("%-9s region %d rel. error %+.3f %+.3f %+.3f\n", name, r, m[r].r / pt[r].r - 1.0,
                  m[r].g / pt[r].g - 1.0, m[r].b / pt[r].b - 1.0);
    std::printf("%-9s relMSE %.5f (block 4: %.5f)\n", name,
                compare_images(*image, *reference_).relmse,
                compare_images(*image, *reference_, 4).relmse);
  }
}

// The control that shows the contrast test can fail: the walk on a copy of the scene without the
// texture (a walk that ignored it and used the base colour factor, white), rendered by the raster
// with the texture (so the wall itself is still red | blue): the floor's contrast collapses.
TEST_F(TextureBleeding, AWalkIgnoringTheTextureLosesTheContrast) {
  Scene untextured = *scene_;
  for (Material& m : untextured.materials) m.base_color_texture = -1;
  const RayScene rays(untextured);
  const VplSet vpls = quasi_random_walk(untextured, rays, {kPaths, 64}, *log_);
  const Image image = raster(vpls);
  const RegionMeans m = region_means(image, *region_);
  picture("ext_texture_bleeding_control.png", {reference_, &image});
  print("no-tex", m);
  std::printf("contrast without the texture in the walk %.3f\n", contrast(m));
  // Measured 1.000: the floor's colour comes from the walk alone, and the assertion above (> 1.25)
  // would fail.
  EXPECT_NEAR(contrast(m), 1.0, 0.02);
  EXPECT_LT(contrast(m), 1.25);
}

} // namespace IRAD_UNITY_ID
} // namespace irad
