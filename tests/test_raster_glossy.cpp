// The raster's glossy light (design.md 1b; raster/glsl/deferred_shaders.h and shaders.h
// vpl_fragment): f_r at the receiver from the G-buffer's material channels, and the glossy VPLs'
// lobes, against rt-vpl over the very same VPLs (walk/estimators/vpl_tracer.h), which evaluates
// core's C++ BRDF: the two may differ by the shadow maps' error and single-precision round-off
// only.
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/image/image_metrics.h"
#include "core/scene/scene_builder.h"
#include "raster/raster_renderer.h"
#include "raster/ring_renderer.h"
#include "tests/test_paths.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/rays/ray_scene.h"
#include "walk/vpls/quasi_random_walk.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>

namespace irad {
namespace IRAD_UNITY_ID {

Log quiet() {
  return Log([](const std::string&) {});
}

RasterOptions options(int batch, int interleave) {
  RasterOptions o;
  o.batch = batch;
  o.interleave = interleave;
  o.shadow_resolution = 256;
  return o;
}

void print(const char* what, const ImageMetrics& m) {
  std::printf("%s: relMSE %.2e, rmse %.2e, means %.4f %.4f %.4f\n", what, m.relmse, m.rmse,
              m.mean_ratio[0], m.mean_ratio[1], m.mean_ratio[2]);
}

// The set with every VPL drawn as its Lambertian proxy (no lobes).
VplSet without_lobes(VplSet set) {
  set.lobes.clear();
  for (Vpl& v : set.vpls) v.lobe = -1;
  return set;
}

struct Cornell {
  Scene scene;
  View view;
  VplSet vpls;
  Image rt;
};

// data/cornell_glossy.gltf (metal and plastic blocks, semi-gloss floor) at 64x64, 128 paths.
const Cornell& glossy_cornell() {
  static const Cornell cornell = [] {
    Log log = quiet();
    Cornell c{
        load_gltf(std::filesystem::path(IRAD_SOURCE_DIR) / "data" / "cornell_glossy.gltf", log),
        {},
        {},
        {}};
    c.view = make_view(c.scene.cameras[0], c.scene.bounds, 64, 64);
    const RayScene rays(c.scene);
    WalkOptions w;
    w.paths = 128;
    c.vpls = quasi_random_walk(c.scene, rays, w, log);
    c.rt = trace_vpls(c.scene, rays, c.view, c.vpls, {});
    return c;
  }();
  return cornell;
}

// Every VPL on every pixel (interleave 1), by the per-VPL passes and by the batched deferred
// ones, against rt-vpl; and the same with the blocks' specular lobes left to the glossy camera
// pass (RasterOptions::traced_roughness: their diffuse lobe alone from the VPLs a ray meets).
TEST(RasterGlossy, EqualsRtVplOverTheSameVpls) {
  const Cornell& c = glossy_cornell();
  ASSERT_FALSE(c.scene.all_lambertian());
  ASSERT_FALSE(c.vpls.lobes.empty());
  const RayScene rays(c.scene);
  VplTracerOptions traced;
  traced.traced_roughness = 0.35f;
  const Image rt_traced = trace_vpls(c.scene, rays, c.view, c.vpls, traced);
  EXPECT_GT(compare_images(rt_traced, c.rt).relmse, 1e-2);
  for (const int batch : {1, 16}) {
    RasterOptions o = options(batch, 1);
    o.traced_roughness = traced.traced_roughness;
    const Image raster_traced = RasterRenderer(c.scene, o).render(c.view, c.vpls);
    const ImageMetrics mt = compare_images(raster_traced, rt_traced);
    print("traced lobes: raster vs rt-vpl", mt);
    EXPECT_LT(mt.relmse, 2e-5); // measured 5.1e-6, the same pixels' shadow-map error as below
    EXPECT_GT(compare_images(raster_traced, c.rt).relmse, 1e-2); // the lobes were left out
    RasterTimings t;
    const Image r = RasterRenderer(c.scene, options(batch, 1)).render(c.view, c.vpls, &t);
    EXPECT_EQ(r.non_finite_count(), 0u);
    EXPECT_EQ(t.single_passes, batch == 1 ? t.passes : 0u);
    const ImageMetrics m = compare_images(r, c.rt);
    print(batch == 1 ? "per-VPL passes vs rt-vpl" : "batched passes vs rt-vpl", m);
    // Measured (llvmpipe, R = 256): relMSE 5.1e-6 both ways, means within 2e-4; bounds ~4x.
    EXPECT_LT(m.relmse, 2e-5);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(m.mean_ratio[size_t(ch)], 1.0, 1e-3);
  }
}

// What the lobes and the receivers' BRDF change: drawn as Lambertian proxies the same VPLs miss
// rt-vpl by far more.
TEST(RasterGlossy, LobesAndReceiversMatter) {
  const Cornell& c = glossy_cornell();
  const Image proxies =
      RasterRenderer(c.scene, options(16, 1)).render(c.view, without_lobes(c.vpls));
  Scene lambertian = c.scene;
  for (Material& m : lambertian.materials) m.metallic = m.specular_factor = 0.0f;
  const Image diffuse = RasterRenderer(lambertian, options(16, 1)).render(c.view, c.vpls);
  const ImageMetrics a = compare_images(proxies, c.rt), b = compare_images(diffuse, c.rt);
  print("lobes dropped vs rt-vpl", a);
  print("receivers Lambertian vs rt-vpl", b);
  // Measured: 1.2e-2 and 3.9e-2, means 2 % high: 2000x and 7000x the raster's own difference.
  EXPECT_GT(a.relmse, 5e-3);
  EXPECT_GT(b.relmse, 1e-2);
}

// Interleaved sampling demodulates by the G-buffer's directional albedo: its image keeps the
// channel means of every VPL on every pixel (1024 paths: with 128 the k^2 sets of 8 paths each
// move the means by a few per cent in either direction, on the Lambertian box too).
TEST(RasterGlossy, InterleavedKeepsTheMeans) {
  const Cornell& c = glossy_cornell();
  Log log = quiet();
  const RayScene rays(c.scene);
  WalkOptions w;
  w.paths = 1024;
  const VplSet many = quasi_random_walk(c.scene, rays, w, log);
  const Image full = RasterRenderer(c.scene, options(16, 1)).render(c.view, many);
  for (const int k : {2, 4}) {
    const Image r = RasterRenderer(c.scene, options(16, k)).render(c.view, many);
    const ImageMetrics m = compare_images(r, full);
    std::printf("interleave %d: ", k);
    print("batched vs every VPL", m);
    // Measured: means within 0.4 % at k = 4 (the Lambertian box: 0.4 %); bounds about 4x.
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(m.mean_ratio[size_t(ch)], 1.0, 0.015);
    // The per-VPL passes write the same demodulated light as the batched ones.
    const Image a = RasterRenderer(c.scene, options(1, k)).render(c.view, c.vpls);
    const Image b = RasterRenderer(c.scene, options(16, k)).render(c.view, c.vpls);
    const ImageMetrics same = compare_images(a, b);
    print("  per-VPL vs batched", same);
    EXPECT_LT(same.relmse, 1e-6);
  }
}

// The walk path by path, as the walkthrough traces it (each path's lobes of its own), and all
// paths together (the lobes re-indexed).
struct Paths {
  std::vector<std::vector<Vpl>> vpls;
  std::vector<std::vector<VplLobe>> lobes;
  VplSet all;
};

Paths trace_paths(const Scene& scene, std::uint32_t n) {
  Log log = quiet();
  const RayScene rays(scene);
  const QuasiRandomWalk walk(scene, rays, {n, 64}, log);
  Paths p{std::vector<std::vector<Vpl>>(n), std::vector<std::vector<VplLobe>>(n), walk.header()};
  for (std::uint32_t i = 0; i < n; ++i) {
    walk.trace(i, p.vpls[i], &p.lobes[i]);
    const auto first = static_cast<std::int32_t>(p.all.lobes.size());
    for (Vpl v : p.vpls[i]) {
      if (v.lobe >= 0) v.lobe += first;
      p.all.vpls.push_back(v);
    }
    p.all.lobes.insert(p.all.lobes.end(), p.lobes[i].begin(), p.lobes[i].end());
  }
  return p;
}

// The walkthrough's modes: shadow maps kept per path and shaded from a camera that has moved
// since (the cached walkthrough re-shades the glossy light toward it), and the ring of path
// images, against one render of all the paths.
TEST(RasterGlossy, KeptShadowMapsAndTheRingShadeTheLobes) {
  const Cornell& c = glossy_cornell();
  const Paths p = trace_paths(c.scene, 48);
  ASSERT_FALSE(p.all.lobes.empty());
  Camera moved = c.scene.cameras[0];
  moved.camera_to_world[3] += glm::vec4(0.1f, -0.05f, 0.0f, 0.0f);
  const View view = make_view(moved, c.scene.bounds, 64, 64);
  for (const int batch : {1, 16}) {
    RasterRenderer renderer(c.scene, options(batch, 1));
    const Image fresh = renderer.render(view, p.all);
    for (std::uint32_t i = 0; i < p.vpls.size(); ++i)
      renderer.cache_path(i, p.vpls[i], 64, 64, p.lobes[i]);
    const ImageMetrics m = compare_images(renderer.render_cached(view), fresh);
    std::printf("batch %d: ", batch);
    print("kept shadow maps vs drawn anew", m);
    // Measured: relMSE 0 with batch 1 and 16.
    EXPECT_LT(m.relmse, 1e-10);
    // The same VPLs as Lambertian proxies give another image.
    EXPECT_GT(compare_images(renderer.render(view, without_lobes(p.all)), fresh).relmse, 1e-3);
  }
  RingOptions o;
  o.paths = 48;
  o.width = o.height = 64;
  o.raster = options(16, 1);
  RingRenderer ring(c.scene, o);
  for (std::uint32_t i = 0; i < p.vpls.size(); ++i) ring.replace(i, p.vpls[i], view, p.lobes[i]);
  const ImageMetrics m =
      compare_images(ring.frame(view), RasterRenderer(c.scene, options(16, 1)).render(view, p.all));
  print("ring vs one render", m);
  EXPECT_LT(m.relmse, 1e-10); // measured: 1.4e-15 (the summation order)
}

// A texture of side n from f(u, v) (texel centres).
template <class F>
int add_texture(Scene& s, int n, F f) {
  Texture t;
  t.width = t.height = n;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      t.texels.push_back(f((float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n)));
  s.textures.push_back(t);
  return int(s.textures.size()) - 1;
}

// A metal floor with a bumpy normal map and a metallic-roughness texture (roughness 0.25..0.75,
// half of it dielectric), a glossy plastic wall and a Lambertian one, lit by a square light:
// every material input the G-buffer carries, and glossy VPLs lighting glossy receivers.
Scene textured_glossy_room() {
  Scene s;
  const std::uint32_t floor = add_material(s, {0.9f, 0.7f, 0.5f});
  add_quad(s, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, floor);
  const std::uint32_t wall = add_material(s, {0.6f, 0.6f, 0.6f});
  add_quad(s, {-1, 1, 0}, {1, 1, 0}, {1, 1, 1.5f}, {-1, 1, 1.5f}, wall);
  const std::uint32_t plastic = add_material(s, {0.2f, 0.3f, 0.8f});
  add_quad(s, {-1, -1, 0}, {-1, 1, 0}, {-1, 1, 1.5f}, {-1, -1, 1.5f}, plastic);
  const std::uint32_t light = add_material(s, glm::vec3(0.0f), glm::vec3(20.0f));
  add_quad(s, {0.2f, -0.3f, 1.2f}, {0.2f, 0.3f, 1.2f}, {0.8f, 0.3f, 1.2f}, {0.8f, -0.3f, 1.2f},
           light);
  s.uvs.resize(s.positions.size());
  for (std::size_t v = 0; v < s.positions.size(); ++v) {
    const glm::vec3& p = s.positions[v];
    s.uvs[v] = {p.x + p.z, p.y + p.z}; // two tiles per floor side
  }
  Material& m = s.materials[floor];
  m.metallic = 1.0f;
  m.roughness = 1.0f;
  m.specular_factor = 1.0f;
  m.normal_texture = add_texture(s, 32, [](float u, float v) {
    const glm::vec3 n =
        glm::normalize(glm::vec3(0.5f * std::sin(12.0f * u), 0.3f * std::cos(9.0f * v), 1.0f));
    return glm::vec4(0.5f * n + 0.5f, 1.0f);
  });
  m.metallic_roughness_texture = add_texture(s, 16, [](float u, float v) {
    return glm::vec4(0.0f, 0.25f + 0.5f * v, u < 0.5f ? 1.0f : 0.0f, 1.0f);
  });
  Material& p = s.materials[plastic];
  p.roughness = 0.3f;
  p.specular_factor = 1.0f;
  p.ior = 1.6f;
  // The floor's tangent: uv's u runs along +x, v along +y (B = w N x T = +y: w = 1); the walls
  // have no normal map.
  s.tangents.assign(s.positions.size(), glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  s.cameras.push_back(look_at({0.9f, -1.6f, 1.3f}, {-0.1f, 0.2f, 0.3f}, {0, 0, 1}, 0.9f));
  finish(s);
  return s;
}

TEST(RasterGlossy, NormalAndMetallicRoughnessMapsEqualRtVpl) {
  const Scene s = textured_glossy_room();
  ASSERT_EQ(s.tangents.size(), s.positions.size());
  Log log = quiet();
  const RayScene rays(s);
  WalkOptions w;
  w.paths = 128;
  const VplSet vpls = quasi_random_walk(s, rays, w, log);
  ASSERT_FALSE(vpls.lobes.empty());
  const View view = make_view(s.cameras[0], s.bounds, 64, 64);
  const Image rt = trace_vpls(s, rays, view, vpls, {});
  for (const int batch : {1, 16}) {
    const Image r = RasterRenderer(s, options(batch, 1)).render(view, vpls);
    const ImageMetrics m = compare_images(r, rt);
    print(batch == 1 ? "textured room, per-VPL vs rt-vpl" : "textured room, batched vs rt-vpl", m);
    // Measured (llvmpipe): relMSE 5.4e-4 and 5.5e-4, means +0.2 %: the bumps' narrow highlights
    // magnify the GPU's bilinear weights (8 bits) against the CPU's exact ones. Bounds ~3x.
    EXPECT_LT(m.relmse, 2e-3);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(m.mean_ratio[size_t(ch)], 1.0, 6e-3);
  }
  // Without the normal map the floor's highlights move: far from rt-vpl's.
  Scene flat = s;
  flat.materials[0].normal_texture = -1;
  const ImageMetrics f =
      compare_images(RasterRenderer(flat, options(16, 1)).render(view, vpls), rt);
  print("textured room without its normal map vs rt-vpl", f);
  EXPECT_GT(f.relmse, 0.1); // measured 0.77
}

} // namespace IRAD_UNITY_ID
} // namespace irad
