// pt against rt-vpl on a glossy Cornell box (design.md 1b): the bundled box with its tall block
// rough metal (metallic 1, roughness 0.3), its short block glossy plastic (roughness 0.2) and its
// floor semi-gloss (roughness 0.45), the walls Lambertian. Both estimators are unbiased with the
// clamp off, so every channel's image mean must agree within their errors; the walk's glossy
// VPLs (narrow lobes, no clamp) are the hard part.
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "test_paths.h"
#include "walk/estimators/path_tracer.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/vpls/quasi_random_walk.h"

#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>

namespace irad {
namespace IRAD_UNITY_ID {

bool inside(const glm::vec3& c, glm::vec3 lo, glm::vec3 hi) {
  return glm::all(glm::greaterThanEqual(c, lo)) && glm::all(glm::lessThanEqual(c, hi));
}

// A material of the box's white with the given metallic and roughness (glTF's specular 1).
std::uint32_t glossy_white(Scene& s, const Material& white, float metallic, float roughness) {
  Material m = white;
  m.metallic = metallic;
  m.roughness = roughness;
  m.specular_factor = 1.0f;
  s.materials.push_back(m);
  return std::uint32_t(s.materials.size() - 1);
}

Scene glossy_cornell(const char* file) {
  Log log([](const std::string&) {});
  Scene s = load_gltf(std::filesystem::path(IRAD_SOURCE_DIR) / "data" / file, log);
  std::uint32_t white = 0;
  while (s.materials[white].name != "white") ++white;
  const Material base = s.materials[white];
  const std::uint32_t metal = glossy_white(s, base, 1.0f, 0.3f);
  const std::uint32_t plastic = glossy_white(s, base, 0.0f, 0.2f);
  const std::uint32_t floor = glossy_white(s, base, 0.0f, 0.45f);
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    if (s.triangle_material[t] != white) continue;
    const glm::uvec3 tri = s.triangles[t];
    const glm::vec3 c = (s.positions[tri.x] + s.positions[tri.y] + s.positions[tri.z]) / 3.0f;
    if (c.y < 1e-4f)
      s.triangle_material[t] = floor;
    else if (inside(c, {0.26f, 0.0f, 0.24f}, {0.48f, 0.331f, 0.46f}))
      s.triangle_material[t] = metal;
    else if (inside(c, {0.08f, 0.0f, 0.06f}, {0.30f, 0.166f, 0.28f}))
      s.triangle_material[t] = plastic;
  }
  return s;
}

glm::dvec3 channel_means(const Image& image) {
  glm::dvec3 sum(0.0);
  for (const glm::vec4& p : image.pixels()) sum += glm::dvec3(p);
  return sum / double(image.pixels().size());
}

struct Means {
  glm::dvec3 pt, rt;
};

Means render_both(const char* file, std::uint32_t spp, std::uint32_t paths) {
  const Scene scene = glossy_cornell(file);
  EXPECT_FALSE(scene.all_lambertian());
  const RayScene rays(scene);
  const View view = make_view(scene.cameras[0], scene.bounds, 48, 48);
  PathTracerOptions o;
  o.spp = spp;
  Means m;
  m.pt = channel_means(path_trace(scene, rays, view, o));
  Log log([](const std::string&) {});
  WalkOptions w;
  w.paths = paths;
  const VplSet vpls = quasi_random_walk(scene, rays, w, log);
  EXPECT_FALSE(vpls.lobes.empty());
  m.rt = channel_means(trace_vpls(scene, rays, view, vpls, {0.0f, 0}));
  std::printf("%s glossy, 48x48: pt %u spp (%.5f %.5f %.5f), rt-vpl N=%u clamp 0 (%.5f %.5f %.5f), "
              "%zu VPLs, %zu glossy; rt/pt - 1: %+.4f %+.4f %+.4f\n",
              file, spp, m.pt.x, m.pt.y, m.pt.z, paths, m.rt.x, m.rt.y, m.rt.z, vpls.vpls.size(),
              vpls.lobes.size(), m.rt.x / m.pt.x - 1.0, m.rt.y / m.pt.y - 1.0,
              m.rt.z / m.pt.z - 1.0);
  return m;
}

TEST(GlossyCornell, PathTracerAndRtVplAgreeInEveryChannelsMean) {
  const Means m = render_both("cornell_box.gltf", 512, 4096);
  for (int c = 0; c < 3; ++c) {
    // Measured: relative differences +0.0013, +0.0043, +0.0008 (R, G, B).
    EXPECT_NEAR(m.rt[c] / m.pt[c], 1.0, 0.01) << "channel " << c;
  }
}

// The same with the red wall a perfect mirror (data/cornell_mirror.gltf): the glossy VPLs'
// mirrored copies reflect their lobes in the mirror plane (core/lights/vpl.h vpl_lobe_shape).
TEST(GlossyCornell, WithAMirrorWallTooPathTracerAndRtVplAgree) {
  const Means m = render_both("cornell_mirror.gltf", 512, 4096);
  for (int c = 0; c < 3; ++c) {
    // Measured: relative differences -0.0051, +0.0000, -0.0043 (R, G, B).
    EXPECT_NEAR(m.rt[c] / m.pt[c], 1.0, 0.015) << "channel " << c;
  }
}

// Lambertian by declaration (metallic 0, specularFactor 0: f_r = rho/pi exactly) takes the diffuse
// code whatever else the material says: the box with every roughness set to 0.2 and every ior to
// 2 renders the same pt and rt-vpl images, bit for bit, and its walk leaves no lobe.
TEST(GlossyCornell, LambertianDeclarationIgnoresRoughnessAndIor) {
  Log log([](const std::string&) {});
  const Scene plain =
      load_gltf(std::filesystem::path(IRAD_SOURCE_DIR) / "data/cornell_box.gltf", log);
  ASSERT_TRUE(plain.all_lambertian());
  Scene declared = plain;
  for (Material& m : declared.materials) {
    m.roughness = 0.2f;
    m.ior = 2.0f;
  }
  ASSERT_TRUE(declared.all_lambertian());
  auto images = [&](const Scene& scene) {
    const RayScene rays(scene);
    const View view = make_view(scene.cameras[0], scene.bounds, 32, 32);
    PathTracerOptions o;
    o.spp = 8;
    WalkOptions w;
    w.paths = 256;
    const VplSet vpls = quasi_random_walk(scene, rays, w, log);
    EXPECT_TRUE(vpls.lobes.empty());
    return std::pair{path_trace(scene, rays, view, o), trace_vpls(scene, rays, view, vpls, {})};
  };
  const auto [pt_a, rt_a] = images(plain);
  const auto [pt_b, rt_b] = images(declared);
  EXPECT_TRUE(pt_a.pixels() == pt_b.pixels());
  EXPECT_TRUE(rt_a.pixels() == rt_b.pixels());
}

} // namespace IRAD_UNITY_ID
} // namespace irad
