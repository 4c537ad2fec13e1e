// glTF alphaMode in the CPU rays (walk/rays/alpha.h, walk/rays/ray_scene.h): Mask cut-outs behave
// like the geometry removed, Blend transmits 1 - a, the walk and light sampling respect both, and
// Blend stays deterministic at any thread count. Scene: a 1 m square light (radiance 1, albedo 0) 1
// m over a 6 m floor (albedo 0.5), facing down, and a 1 m square occluder at half height (albedo 0:
// direct light only on the floor) whose half x > 0 is cut out.
#include "core/animation/animation.h"
#include "core/camera/view.h"
#include "core/scene/scene_builder.h"
#include "core/util/log.h"
#include "walk/compensation/bias_compensation.h"
#include "walk/estimators/path_tracer.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/rays/alpha.h"
#include "walk/rays/ray_scene.h"
#include "walk/vpls/quasi_random_walk.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <memory>
#include <numbers>
#include <vector>

namespace irad {
namespace IRAD_UNITY_ID {

enum class Cut { Removed, BaseAlpha, Texture };

// Adds the quad [x0, x1] x [-0.5, 0.5] at z = 0.5, facing up.
void add_occluder(Scene& s, float x0, float x1, std::uint32_t material) {
  add_quad(s, {x0, -0.5f, 0.5f}, {x1, -0.5f, 0.5f}, {x1, 0.5f, 0.5f}, {x0, 0.5f, 0.5f}, material);
}

Material& mask(Scene& s, std::uint32_t material, float base_alpha) {
  Material& m = s.materials[material];
  m.alpha_mode = AlphaMode::Mask;
  m.alpha_cutoff = 0.5f;
  m.base_alpha = base_alpha;
  return m;
}

// The occluder's x > 0 half: removed, or cut out by base_alpha 0.2 < cutoff 0.5 on its two
// triangles, or by a 4x4 texture whose right two columns have alpha 0 (looked up through
// TEXCOORD_1 and a transform uv' = 2 uv, ClampToEdge: the bilinear alpha crosses 0.5 at x = 0).
Scene occluded_light(Cut cut, float occluder_albedo = 0.0f) {
  Scene s = square_light_over_plane(1.0f, 1.0f, 1.0f, 6.0f, 0.5f);
  const std::uint32_t left = add_material(s, glm::vec3(occluder_albedo));
  if (cut == Cut::Removed) {
    add_occluder(s, -0.5f, 0.0f, left);
  } else if (cut == Cut::BaseAlpha) {
    mask(s, left, 1.0f);
    const std::uint32_t right = add_material(s, glm::vec3(occluder_albedo));
    mask(s, right, 0.2f);
    add_occluder(s, -0.5f, 0.0f, left);
    add_occluder(s, 0.0f, 0.5f, right);
  } else {
    Texture t;
    t.width = t.height = 4;
    t.wrap_s = t.wrap_t = Wrap::ClampToEdge;
    for (int i = 0; i < 16; ++i) t.texels.push_back(glm::vec4(1.0f, 1.0f, 1.0f, i % 4 < 2));
    s.textures.push_back(t);
    Material& m = mask(s, left, 1.0f);
    m.base_color_texture = 0;
    m.base_color_map.texcoord = 1;
    m.base_color_map.matrix = glm::mat3(glm::vec3(2, 0, 0), glm::vec3(0, 2, 0), glm::vec3(0, 0, 1));
    add_occluder(s, -0.5f, 0.5f, left);
    s.uvs1.assign(s.positions.size(), glm::vec2(0.0f));
    for (std::size_t v = s.positions.size() - 4; v < s.positions.size(); ++v)
      s.uvs1[v] = 0.5f * (glm::vec2(s.positions[v]) + 0.5f); // uv' = x + 0.5, y + 0.5
  }
  finish(s);
  return s;
}

// The camera of tests/square_light_error.h: oblique, seeing the floor through the cut-out.
View oblique_view(const Scene& s) {
  return make_view(look_at({0.0f, -3.2f, 2.6f}, {0.0f, 0.0f, 0.2f}, {0, 0, 1}, 0.9f), s.bounds, 96,
                   72);
}

struct Images {
  Image rt_vpl, pt;
};

Images render(const Scene& s, const View& view, std::uint32_t paths = 256, std::uint32_t spp = 16,
              unsigned threads = 0, std::uint64_t seed = 0) {
  Log log([](const std::string&) {});
  const RayScene rays(s);
  const VplSet vpls = quasi_random_walk(s, rays, {paths, 64}, log);
  VplTracerOptions vo;
  vo.threads = threads;
  PathTracerOptions po;
  po.spp = spp;
  po.threads = threads;
  po.seed = seed;
  return {trace_vpls(s, rays, view, vpls, vo), path_trace(s, rays, view, po)};
}

// The floor point seen through pixel (x, y), if the ray meets the floor before anything of the
// Removed scene (the light, the occluder's x < 0 half), with a 2 cm margin around both.
std::optional<glm::dvec3> floor_point(const View& view, int x, int y) {
  const CameraRay ray = pixel_ray(view, x, y);
  const glm::dvec3 o(ray.origin), d(ray.direction);
  if (d.z >= 0.0) return std::nullopt;
  for (const double z : {1.0, 0.5}) {
    const glm::dvec3 q = o + ((z - o.z) / d.z) * d;
    const double x_hi = z == 1.0 ? 0.52 : 0.02;
    if ((z - o.z) / d.z > 0 && q.x > -0.52 && q.x < x_hi && std::abs(q.y) < 0.52)
      return std::nullopt;
  }
  const glm::dvec3 p = o + (-o.z / d.z) * d;
  if (std::abs(p.x) > 2.9 || std::abs(p.y) > 2.9) return std::nullopt;
  return p;
}

// rho E / pi at floor point p with |p.y| <= 0.5 under the Removed occluder: from p the occluder
// (at half height) hides the light's part x < -p.x, so the light seen is [max(-p.x, -0.5), 0.5] x
// [-0.5, 0.5] at z = 1 (Lambert's formula, design.md section 3).
double lambert(const glm::dvec3& p) {
  const double x0 = glm::clamp(-p.x, -0.5, 0.5);
  if (x0 >= 0.5) return 0.0;
  const std::vector<glm::dvec3> visible = {
      {x0, -0.5, 1.0}, {x0, 0.5, 1.0}, {0.5, 0.5, 1.0}, {0.5, -0.5, 1.0}};
  return 0.5 / std::numbers::pi * polygon_irradiance(visible, p, {0, 0, 1}, 1.0);
}

// Whether every light point y sees p at cos_y >= 0.53 (|y - p| <= 1.9): farther out the path
// tracer's next-event shadow ray, offset by eps along the receiver's normal but aimed from the
// unshifted point, meets the light's own plane eps / cos_y before the sample when cos_y < 1/2
// (a bias of the path tracer there, independent of alpha; reported, not fixed here).
bool steep(const glm::dvec3& p) {
  const double dx = std::abs(p.x) + 0.5, dy = std::abs(p.y) + 0.5;
  return dx * dx + dy * dy + 1.0 <= 1.9 * 1.9;
}

struct Difference {
  double max_abs = 0.0, mean = 0.0;
};

Difference difference(const Image& a, const Image& b) {
  Difference d;
  for (std::size_t i = 0; i < a.pixels().size(); ++i) {
    const double e = a.pixels()[i].r - b.pixels()[i].r;
    d.max_abs = std::max(d.max_abs, std::abs(e));
    d.mean += e / static_cast<double>(a.pixels().size());
  }
  return d;
}

// Relative RMS error against lambert() over the floor band |y| <= 0.5 where the light is seen;
// mean: the mean relative error there.
double lambert_rel_rms(const Image& image, const View& view, double* mean = nullptr) {
  double sum_sq = 0.0, sum = 0.0;
  int count = 0;
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const auto p = floor_point(view, x, y);
      if (!p || std::abs(p->y) > 0.5 || !steep(*p)) continue;
      const double expected = lambert(*p);
      if (expected < 0.01) continue; // the umbra and its edge: relative error meaningless
      const double rel = image.at(x, y).r / expected - 1.0;
      sum_sq += rel * rel;
      sum += rel;
      ++count;
    }
  EXPECT_GT(count, 100);
  if (mean != nullptr) *mean = sum / count;
  return std::sqrt(sum_sq / count);
}

TEST(Alpha, FiltersOnlyWithMaskOrBlend) {
  const Scene opaque = occluded_light(Cut::Removed);
  const Scene masked = occluded_light(Cut::BaseAlpha);
  EXPECT_FALSE(RayScene(opaque).has_alpha());
  EXPECT_TRUE(RayScene(masked).has_alpha());
  // Coverage through the texture map: alpha 1 left of x = 0, 0 right of it.
  const Scene textured = occluded_light(Cut::Texture);
  const std::size_t t = textured.triangle_count() - 2;            // (p0 p1 p2) of the occluder
  EXPECT_FLOAT_EQ(coverage_at(textured, t, {0.1f, 0.0f}), 1.0f);  // x = -0.4
  EXPECT_FLOAT_EQ(coverage_at(textured, t, {0.9f, 0.05f}), 0.0f); // x = 0.45
}

class MaskCut : public ::testing::TestWithParam<Cut> {};

// pt and rt-vpl of the cut-out scene against the same scene with the half removed, and against
// Lambert's formula. The images equal those of the removed geometry exactly: the same particle
// and pixel rays meet the same surfaces (rho_bar, hence n_j, differs by the cut-out's area, but
// VPLs of depth >= 1 light nothing visible: the floor is flat, light and occluder have albedo 0).
TEST_P(MaskCut, EqualsRemovedGeometryAndLambert) {
  const Scene removed = occluded_light(Cut::Removed);
  const Scene cut = occluded_light(GetParam());
  const View view = oblique_view(removed);
  const Images a = render(cut, view, 256, 64), b = render(removed, view, 256, 64);
  const Difference rt = difference(a.rt_vpl, b.rt_vpl), pt = difference(a.pt, b.pt);
  double rt_mean = 0.0, pt_mean = 0.0;
  const double rt_rms = lambert_rel_rms(a.rt_vpl, view, &rt_mean);
  const double pt_rms = lambert_rel_rms(a.pt, view, &pt_mean);
  std::printf("mask (%s): vs removed max |d| rt-vpl %.3g pt %.3g; vs Lambert rel RMS / mean "
              "rt-vpl %.4f / %+.4f, pt %.4f / %+.4f\n",
              GetParam() == Cut::BaseAlpha ? "base_alpha" : "texture", rt.max_abs, pt.max_abs,
              rt_rms, rt_mean, pt_rms, pt_mean);
  // Measured 0 for both (bit-identical images), both cuts.
  EXPECT_LE(rt.max_abs, 1e-6);
  EXPECT_LE(pt.max_abs, 1e-6);
  // rt-vpl (256 paths, deterministic): rel RMS 0.0097, mean -0.0074 (quasi-Monte Carlo error of
  // the light's 256 points, half of them hidden near the penumbra). Bounds 0.02 and 0.015.
  EXPECT_LT(rt_rms, 0.02);
  EXPECT_LT(std::abs(rt_mean), 0.015);
  // pt at 64 spp, seeds 0..5: rel RMS 0.073..0.106 (noise), mean -0.0086..+0.0108 (std 0.008).
  // Bounds 0.15 and 0.03 (about 3.5 standard deviations).
  EXPECT_LT(pt_rms, 0.15);
  EXPECT_LT(std::abs(pt_mean), 0.03);
}

INSTANTIATE_TEST_SUITE_P(Alpha, MaskCut, ::testing::Values(Cut::BaseAlpha, Cut::Texture),
                         [](const ::testing::TestParamInfo<Cut>& p) {
                           return std::string(p.param == Cut::BaseAlpha ? "BaseAlpha" : "Texture");
                         });

// The walkthrough's refit geometry: an animated scene keeps its moving triangles in a second
// Embree geometry (walk/rays/ray_scene.h), and both carry the filter. The cut-out occluder moving
// (the second geometry) or still (the first, with floor and light moving), posed and refitted,
// gives the images of the static scene with the half removed.
TEST(Alpha, AnimatedGeometriesFilteredToo) {
  const Scene removed = occluded_light(Cut::Removed);
  const View view = oblique_view(removed);
  const Images reference = render(removed, view, 256, 4);
  for (const bool occluder_moves : {true, false}) {
    Scene s = occluded_light(Cut::BaseAlpha);
    auto animation = std::make_shared<Animation>();
    animation->nodes.emplace_back(); // identity: node-local = world
    Animation::MeshPart part{0, {}, {}, {}};
    for (std::uint32_t v = 0; v < s.positions.size(); ++v)
      if ((v >= 8) == occluder_moves) { // vertices 0..7: floor and light; 8..15: the occluder
        part.vertices.push_back(v);
        part.positions.push_back(s.positions[v]);
        part.normals.push_back(s.normals[v]);
      }
    animation->parts.push_back(part);
    s.animation = animation;
    RayScene rays(s);
    animation->pose(0.0f, s);
    rays.update(s);
    Log log([](const std::string&) {});
    const VplSet vpls = quasi_random_walk(s, rays, {256, 64}, log);
    PathTracerOptions po;
    po.spp = 4;
    const Difference rt = difference(trace_vpls(s, rays, view, vpls, {}), reference.rt_vpl);
    const Difference pt = difference(path_trace(s, rays, view, po), reference.pt);
    std::printf("animated (%s moves): vs static removed max |d| rt-vpl %.3g pt %.3g\n",
                occluder_moves ? "occluder" : "floor and light", rt.max_abs, pt.max_abs);
    EXPECT_LE(rt.max_abs, 1e-6);
    EXPECT_LE(pt.max_abs, 1e-6);
  }
}

// The walk's particles pass through the cut-out: with an occluder of albedo 0.5 some VPLs lie on
// its kept half, none on the cut-out half.
TEST(Alpha, WalkPassesThroughCutouts) {
  for (const Cut cut : {Cut::BaseAlpha, Cut::Texture}) {
    const Scene s = occluded_light(cut, 0.5f);
    Log log([](const std::string&) {});
    const RayScene rays(s);
    const VplSet vpls = quasi_random_walk(s, rays, {1024, 64}, log);
    int kept = 0, cut_out = 0;
    for (const Vpl& v : vpls.vpls) {
      if (std::abs(v.position.z - 0.5f) > 1e-4f) continue;
      (v.position.x < 0.0f ? kept : cut_out) += 1;
    }
    std::printf("walk through cut-out: %d VPLs on the kept half, %d on the cut-out half\n", kept,
                cut_out);
    // Measured 118 and 0 (both cuts).
    EXPECT_GT(kept, 50);
    EXPECT_EQ(cut_out, 0);
  }
}

// A Blend occluder (base_alpha a, the whole 1 m square, albedo 0) or none (a < 0), seen from a
// camera below the occluder (it sees only the floor under it, never through it).
Scene blend_occluder(float a, AlphaMode mode = AlphaMode::Blend) {
  Scene s = square_light_over_plane(1.0f, 1.0f, 1.0f, 6.0f, 0.5f);
  if (a >= 0.0f) {
    const std::uint32_t m = add_material(s, glm::vec3(0.0f));
    s.materials[m].alpha_mode = mode;
    s.materials[m].base_alpha = a;
    add_occluder(s, -0.5f, 0.5f, m);
  }
  finish(s);
  return s;
}

View low_view(const Scene& s) {
  return make_view(look_at({0.0f, -1.6f, 0.4f}, {0.0f, 0.0f, 0.0f}, {0, 0, 1}, 0.9f), s.bounds, 96,
                   72);
}

// Mean over the pixels that see the floor at |x|, |y| <= 0.45: there an opaque occluder hides the
// whole light (its shadow from every light point covers [-0.5, 0.5]^2).
double umbra_mean(const Image& image, const View& view) {
  double sum = 0.0;
  int count = 0;
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const CameraRay ray = pixel_ray(view, x, y);
      const glm::dvec3 o(ray.origin), d(ray.direction);
      if (d.z >= 0.0) continue;
      const glm::dvec3 p = o + (-o.z / d.z) * d;
      if (std::abs(p.x) > 0.45 || std::abs(p.y) > 0.45) continue;
      sum += image.at(x, y).r;
      ++count;
    }
  EXPECT_GT(count, 400); // 484 at 96x72
  return sum / count;
}

// Blend with a = 0.25: each ray stops at the occluder with probability 0.25, so the umbra
// receives 0.75 of the unoccluded direct light (the only light there: the occluder's albedo is 0).
TEST(Alpha, BlendTransmitsOneMinusCoverage) {
  const Scene open = blend_occluder(-1.0f), blend = blend_occluder(0.25f);
  const Scene opaque = blend_occluder(1.0f, AlphaMode::Opaque);
  const View view = low_view(open);
  const Images a = render(blend, view, 256, 16), b = render(open, view, 256, 16);
  const Images c = render(opaque, view, 256, 16);
  const double rt = umbra_mean(a.rt_vpl, view) / umbra_mean(b.rt_vpl, view);
  const double pt = umbra_mean(a.pt, view) / umbra_mean(b.pt, view);
  const double rt0 = umbra_mean(c.rt_vpl, view), pt0 = umbra_mean(c.pt, view);
  std::printf("blend a = 0.25: umbra / unoccluded rt-vpl %.4f pt %.4f (opaque: %.3g %.3g)\n", rt,
              pt, rt0, pt0);
  // rt-vpl: 0.7532, 0.7518, 0.7513, 0.7506 at 128, 256, 512, 1024 paths (each shadow ray a
  // Bernoulli trial: about 484 pixels x 256 light VPLs). Bound 0.006.
  EXPECT_NEAR(rt, 0.75, 0.006);
  // pt at 16 spp, seeds 0..7: 0.7423..0.7596, mean 0.7512, std 0.0053. Bound 0.02 (3.8 std).
  EXPECT_NEAR(pt, 0.75, 0.02);
  // An opaque occluder leaves the umbra black (no light reaches it by any path): exactly 0.
  EXPECT_EQ(rt0, 0.0);
  EXPECT_EQ(pt0, 0.0);
}

// RayScene::occluded over many segments from one origin (packets of 8, the light rows' and
// rt-vpl's shadow rays) answers as the single-ray query does, the alpha filters included: Blend
// (a = 0.25, hashed per ray), a Mask texture cut-out and no alpha at all, with two salts.
TEST(Alpha, PacketsAnswerAsSingleRays) {
  const Scene scenes[] = {blend_occluder(0.25f), occluded_light(Cut::Texture),
                          occluded_light(Cut::Removed)};
  for (const Scene& s : scenes) {
    const RayScene rays(s);
    std::size_t blocked_count = 0, total = 0;
    for (int i = 0; i < 16; ++i) {
      const glm::vec3 origin(-0.9f + 0.12f * float(i), 0.05f * float(i % 5) - 0.1f, 0.0f);
      std::vector<glm::vec3> directions;
      std::vector<float> tmax;
      for (int j = 0; j < 37; ++j) { // not a multiple of the packet: a partial last packet
        const glm::vec3 target(-0.45f + 0.025f * float(j), 0.3f * std::sin(float(j)), 1.0f);
        directions.push_back(glm::normalize(target - origin));
        tmax.push_back(glm::length(target - origin) - 1e-3f);
      }
      for (const std::uint64_t salt : {0ull, 12345ull}) {
        bool blocked[37] = {};
        rays.occluded(origin, directions.data(), tmax.data(), directions.size(), 1e-4f, blocked,
                      salt);
        for (std::size_t j = 0; j < directions.size(); ++j) {
          const bool single = rays.occluded(origin, directions[j], 1e-4f, tmax[j], salt);
          ASSERT_EQ(blocked[j], single) << s.materials.size() << " " << i << " " << j;
          blocked_count += single;
          ++total;
        }
      }
    }
    std::printf("packets: %zu of %zu segments blocked\n", blocked_count, total);
    EXPECT_GT(blocked_count, 0u); // each scene blocks some segments and not others
    EXPECT_LT(blocked_count, total);
  }
}

// Blend decisions hash the ray, never a shared counter: the same images at 1 and 2 threads.
TEST(Alpha, BlendDeterministicAtAnyThreadCount) {
  const Scene s = blend_occluder(0.25f);
  const View view = make_view(look_at({0.0f, -3.2f, 2.6f}, {0.0f, 0.0f, 0.2f}, {0, 0, 1}, 0.9f),
                              s.bounds, 48, 36);
  const Images one = render(s, view, 64, 4, 1), two = render(s, view, 64, 4, 2);
  EXPECT_EQ(one.rt_vpl.pixels(), two.rt_vpl.pixels());
  EXPECT_EQ(one.pt.pixels(), two.pt.pixels());
}

// A light whose x > 0 half is cut out (Mask, base_alpha 0) against the light with that half
// removed: light samples on the cut-out half carry nothing, so both estimate the same image.
Scene half_light(bool masked) {
  Scene s;
  const std::uint32_t floor = add_material(s, glm::vec3(0.5f));
  const std::uint32_t light = add_material(s, glm::vec3(0.0f), glm::vec3(1.0f));
  add_quad(s, {-3, -3, 0}, {3, -3, 0}, {3, 3, 0}, {-3, 3, 0}, floor);
  auto add_light = [&](float x0, float x1, std::uint32_t m) {
    add_quad(s, {x0, -0.5f, 1.0f}, {x0, 0.5f, 1.0f}, {x1, 0.5f, 1.0f}, {x1, -0.5f, 1.0f}, m);
  };
  add_light(-0.5f, 0.0f, light);
  if (masked) {
    const std::uint32_t cut = add_material(s, glm::vec3(0.0f), glm::vec3(1.0f));
    mask(s, cut, 0.0f);
    add_light(0.0f, 0.5f, cut);
  }
  finish(s);
  return s;
}

double image_mean(const Image& image) {
  double sum = 0.0;
  for (const glm::vec4& p : image.pixels()) sum += p.r;
  return sum / static_cast<double>(image.pixels().size());
}

TEST(Alpha, MaskedEmitterEqualsRemovedHalf) {
  const Scene masked = half_light(true), removed = half_light(false);
  const View view = oblique_view(removed);
  const Images a = render(masked, view), b = render(removed, view);
  const double rt = image_mean(a.rt_vpl) / image_mean(b.rt_vpl) - 1.0;
  const double pt = image_mean(a.pt) / image_mean(b.pt) - 1.0;
  Log log([](const std::string&) {});
  const RayScene rays(masked);
  int on_cut = 0;
  for (const Vpl& v : quasi_random_walk(masked, rays, {256, 64}, log).vpls)
    if (v.depth == 0 && v.position.x > 0.0f) ++on_cut;
  std::printf("masked emitter: image mean vs removed half rt-vpl %+.4f pt %+.4f; %d light VPLs on "
              "the cut-out half\n",
              rt, pt, on_cut);
  EXPECT_EQ(on_cut, 0);
  // rt-vpl (deterministic): +0.0023, the two lights' different quasi-random points. Bound 0.01.
  EXPECT_LT(std::abs(rt), 0.01);
  // pt at 16 spp, seeds 0..7: -0.0184..+0.0164 (std 0.012). Bound 0.045 (3.7 std).
  EXPECT_LT(std::abs(pt), 0.045);
}

// The residual gather (walk/compensation/bias_compensation.h) with d_min = 0.15 x 6.2 m = 1.28 m:
// its rays from the floor reach the light (1 m up) through the cut-out, and see what they see with
// the half removed (the residual there is emission only: light and occluder have albedo 0, so the
// VPL sets' different n_j do not enter). Measured: equal (max |d| 0), mean 0.00081 per pixel.
TEST(Alpha, ResidualGatherThroughCutout) {
  const Scene removed = occluded_light(Cut::Removed), cut = occluded_light(Cut::Texture);
  const View view = oblique_view(removed);
  Log log([](const std::string&) {});
  const RayScene rays_a(cut), rays_b(removed);
  const VplSet a = quasi_random_walk(cut, rays_a, {64, 64}, log);
  const VplSet b = quasi_random_walk(removed, rays_b, {64, 64}, log);
  const BiasCompensationOptions options{0.15f, 4, 0, 0, 16};
  const Image ra = clamp_residual(cut, rays_a, view, a, options);
  const Image rb = clamp_residual(removed, rays_b, view, b, options);
  const double mean = image_mean(rb);
  std::printf("residual through the cut-out: max |d| %.3g, mean %.4g\n", difference(ra, rb).max_abs,
              mean);
  EXPECT_LE(difference(ra, rb).max_abs, 1e-6);
  EXPECT_GT(mean, 0.0);
}

// Blend in the walk: the same particles (same Halton points, same rho_bar) meet an occluder of
// albedo 0.5; with a = 0.25 each first hit on it stops with probability 0.25, so its depth-1 VPLs
// number 0.25 of those on the opaque occluder.
TEST(Alpha, WalkStopsAtBlendWithProbabilityCoverage) {
  auto on_occluder = [](float a, AlphaMode mode) {
    Scene s = square_light_over_plane(1.0f, 1.0f, 1.0f, 6.0f, 0.5f);
    const std::uint32_t m = add_material(s, glm::vec3(0.5f));
    s.materials[m].alpha_mode = mode;
    s.materials[m].base_alpha = a;
    add_occluder(s, -0.5f, 0.5f, m);
    finish(s);
    Log log([](const std::string&) {});
    const RayScene rays(s);
    int count = 0;
    for (const Vpl& v : quasi_random_walk(s, rays, {4096, 64}, log).vpls)
      count += v.depth == 1 && std::abs(v.position.z - 0.5f) < 1e-4f;
    return count;
  };
  const int opaque = on_occluder(1.0f, AlphaMode::Opaque);
  const int blend = on_occluder(0.25f, AlphaMode::Blend);
  const double ratio = double(blend) / opaque;
  std::printf("walk: depth-1 VPLs on the occluder, blend %d / opaque %d = %.4f\n", blend, opaque,
              ratio);
  // Measured 229 / 826 = 0.2772; 0.2593, 0.2749, 0.2539, 0.2486 at N = 1024, 2048, 8192, 16384
  // (216..3319 opaque hits): binomial noise, std sqrt(0.25 * 0.75 / 826) = 0.015 here. Bound 0.06
  // (4 std).
  EXPECT_NEAR(ratio, 0.25, 0.06);
}

} // namespace IRAD_UNITY_ID
} // namespace irad
