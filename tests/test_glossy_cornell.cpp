// pt against rt-vpl on a glossy Cornell box (design.md 1b): the bundled box with its tall block
// rough metal (metallic 1, roughness 0.3), its short block glossy plastic (roughness 0.2) and its
// floor semi-gloss (roughness 0.45), the walls Lambertian. Both estimators are unbiased with the
// clamp off, so every channel's image mean must agree within their errors; the walk's glossy
// VPLs (narrow lobes, no clamp) are the hard part.
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "test_paths.h"
#include "walk/path_tracer.h"
#include "walk/quasi_random_walk.h"
#include "walk/vpl_tracer.h"

#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>

namespace irad {
namespace {

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

Scene glossy_cornell() {
  Log log([](const std::string&) {});
  Scene s = load_gltf(std::filesystem::path(IRAD_SOURCE_DIR) / "data/cornell_box.gltf", log);
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

TEST(GlossyCornell, PathTracerAndRtVplAgreeInEveryChannelsMean) {
  const Scene scene = glossy_cornell();
  ASSERT_FALSE(scene.all_lambertian());
  const RayScene rays(scene);
  const View view = make_view(scene.cameras[0], scene.bounds, 48, 48);
  PathTracerOptions o;
  o.spp = 512;
  const glm::dvec3 pt = channel_means(path_trace(scene, rays, view, o));
  Log log([](const std::string&) {});
  WalkOptions w;
  w.paths = 4096;
  const VplSet vpls = quasi_random_walk(scene, rays, w, log);
  EXPECT_FALSE(vpls.lobes.empty());
  const glm::dvec3 rt = channel_means(trace_vpls(scene, rays, view, vpls, {0.0f, 0}));
  std::printf("glossy Cornell 48x48: pt 512 spp (%.5f %.5f %.5f), rt-vpl N=4096 clamp 0 "
              "(%.5f %.5f %.5f), %zu VPLs, %zu glossy\n",
              pt.x, pt.y, pt.z, rt.x, rt.y, rt.z, vpls.vpls.size(), vpls.lobes.size());
  for (int c = 0; c < 3; ++c) {
    // Measured: relative differences +0.0013, +0.0042, +0.0007 (R, G, B).
    EXPECT_NEAR(rt[c] / pt[c], 1.0, 0.01) << "channel " << c;
  }
}

} // namespace
} // namespace irad
