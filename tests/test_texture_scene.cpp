// The texture sampler and the scene model's surface queries.
#include "core/material/brdf.h"
#include "core/material/surface_material.h"
#include "core/scene/scene.h"
#include "core/scene/texture.h"
#include "tests/gltf_test_scene.h"

#include <cmath>
#include <cstdint>
#include <gtest/gtest.h>
#include <limits>
#include <vector>

namespace IRAD_UNITY_ID {

using namespace gltf_test;
using irad::Scene;
// ---------------------------------------------------------------------------------------------

// 2x2 texture a b / c d.
irad::Texture two_by_two(irad::Wrap s, irad::Wrap t) {
  irad::Texture tex;
  tex.width = 2;
  tex.height = 2;
  tex.texels = {glm::vec4(1, 0, 0, 1), glm::vec4(0, 1, 0, 1), glm::vec4(0, 0, 1, 1),
                glm::vec4(1, 1, 1, 0)};
  tex.wrap_s = s;
  tex.wrap_t = t;
  return tex;
}

TEST(Texture, SrgbToLinearIsThePiecewiseEotf) {
  EXPECT_EQ(irad::srgb_to_linear(0.0f), 0.0f);
  EXPECT_NEAR(irad::srgb_to_linear(1.0f), 1.0f, 1e-7f);
  EXPECT_NEAR(irad::srgb_to_linear(0.04045f), 0.04045f / 12.92f, 1e-9f);
  EXPECT_NEAR(irad::srgb_to_linear(0.5f), 0.2140411f, 1e-6f);
  EXPECT_NEAR(irad::srgb_to_linear(0.0404f), irad::srgb_to_linear(0.0405f), 1e-5f); // continuous
}

TEST(Texture, BilinearWithTexelCentres) {
  const irad::Texture t = two_by_two(irad::Wrap::Repeat, irad::Wrap::Repeat);
  expect_near(t.sample({0.25f, 0.25f}), t.texels[0]);
  expect_near(t.sample({0.75f, 0.25f}), t.texels[1]);
  expect_near(t.sample({0.25f, 0.75f}), t.texels[2]);
  expect_near(t.sample({0.5f, 0.25f}), 0.5f * (t.texels[0] + t.texels[1]));
  expect_near(t.sample({0.5f, 0.5f}), t.mean());
  expect_near(t.mean(), glm::vec4(0.5f, 0.5f, 0.5f, 0.75f));
}

TEST(Texture, WrapModes) {
  using irad::Wrap;
  const irad::Texture repeat = two_by_two(Wrap::Repeat, Wrap::Repeat);
  const irad::Texture clamp = two_by_two(Wrap::ClampToEdge, Wrap::ClampToEdge);
  const irad::Texture mirror = two_by_two(Wrap::MirroredRepeat, Wrap::MirroredRepeat);
  const glm::vec4 a = repeat.texels[0], b = repeat.texels[1];
  // u = 0: between texel -1 and 0.
  expect_near(repeat.sample({0.0f, 0.25f}), 0.5f * (a + b));
  expect_near(clamp.sample({0.0f, 0.25f}), a);
  expect_near(mirror.sample({0.0f, 0.25f}), a);
  // u = 1.25 and u = -0.25.
  expect_near(repeat.sample({1.25f, 0.25f}), a);
  expect_near(clamp.sample({1.25f, 0.25f}), b);
  expect_near(mirror.sample({1.25f, 0.25f}), b);
  expect_near(repeat.sample({-0.25f, 0.25f}), b);
  expect_near(clamp.sample({-0.25f, 0.25f}), a);
  expect_near(mirror.sample({-0.25f, 0.25f}), a);
  expect_near(mirror.sample({2.25f, 0.25f}), a); // period 2
  expect_near(mirror.sample({-1.25f, 0.25f}), b);
  // v wraps the same way: v = 1.25 is row 0 under repeat, row 1 under clamp and mirror.
  expect_near(repeat.sample({0.25f, 1.25f}), a);
  expect_near(clamp.sample({0.25f, 1.25f}), repeat.texels[2]);
  expect_near(mirror.sample({0.25f, 1.25f}), repeat.texels[2]);
}

TEST(Texture, NonFiniteAndHugeCoordinates) {
  for (irad::Wrap w : {irad::Wrap::Repeat, irad::Wrap::ClampToEdge, irad::Wrap::MirroredRepeat}) {
    const irad::Texture t = two_by_two(w, w);
    const float inf = std::numeric_limits<float>::infinity();
    expect_near(t.sample({kNaN, kNaN}), t.sample({0, 0}));
    expect_near(t.sample({inf, -inf}), t.sample({0, 0}));
    for (float huge : {1e30f, -1e30f, 3e38f}) {
      const glm::vec4 v = t.sample({huge, huge});
      EXPECT_TRUE(std::isfinite(v.x + v.y + v.z + v.w));
    }
  }
  EXPECT_EQ(irad::Texture{}.sample({0.5f, 0.5f}), glm::vec4(0.0f));
}

// ---------------------------------------------------------------------------------------------

// Two triangles: a right triangle of area 2 (albedo 0.5) and one of area 1 (albedo 0.8, emissive).
Scene two_triangles() {
  Scene s;
  s.positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 1}, {1, 0, 1}, {0, 2, 1}};
  s.normals.assign(6, glm::vec3(0, 0, 1));
  s.triangles = {{0, 1, 2}, {3, 4, 5}};
  s.triangle_material = {0, 1};
  irad::Material grey;
  grey.base_color = glm::vec3(0.5f);
  irad::Material lamp;
  lamp.base_color = glm::vec3(0.8f);
  lamp.emission = glm::vec3(3.0f);
  s.materials = {grey, lamp};
  return s;
}

TEST(SceneModel, AreaNormalAndEmitters) {
  const Scene s = two_triangles();
  EXPECT_FLOAT_EQ(irad::triangle_area(s, 0), 2.0f);
  EXPECT_FLOAT_EQ(irad::triangle_area(s, 1), 1.0f);
  expect_near(irad::geometric_normal(s, 0), {0, 0, 1});
  EXPECT_TRUE(s.has_emitters());
  Scene flat = s;
  flat.positions[5] = {2, 0, 1}; // the emitter collapses to a segment
  EXPECT_FALSE(flat.has_emitters());
  Scene clockwise = s;
  clockwise.triangles[0] = {0, 2, 1};
  expect_near(irad::geometric_normal(clockwise, 0), {0, 0, -1});
}

TEST(SceneModel, MeanAlbedoIsAreaWeighted) {
  const Scene s = two_triangles();
  EXPECT_NEAR(irad::mean_albedo(s), (2 * 0.5 + 1 * 0.8) / 3.0, 1e-6);
  EXPECT_EQ(irad::mean_albedo(Scene{}), 0.0);
  Scene coloured = s;
  coloured.materials[0].base_color = {0.9f, 0.3f, 0.0f}; // mean 0.4
  EXPECT_NEAR(irad::mean_albedo(coloured), (2 * 0.4 + 1 * 0.8) / 3.0, 1e-6);
}

// The per-material sums against every triangle's albedo taken on its own (brdf_inputs_at at the
// centroid, hemispherical_albedo): a metal used by two triangles, a Lambertian one and an unused
// material, without and with COLOR_0 (which the BRDF's Fresnel terms do not take linearly).
TEST(SceneModel, MeanAlbedoOfBrdfsAndVertexColoursPerTriangle) {
  Scene s = two_triangles();
  s.positions.insert(s.positions.end(), {{0, 0, 2}, {1, 0, 2}, {0, 1, 2}});
  s.normals.assign(9, glm::vec3(0, 0, 1));
  s.triangles.push_back({6, 7, 8}); // area 0.5
  s.triangle_material = {0, 1, 0};
  s.materials[0].metallic = 1.0f;
  s.materials[0].roughness = 0.4f;
  s.materials[0].base_color = {0.9f, 0.6f, 0.2f};
  s.materials.push_back(irad::Material{}); // unused
  auto expected = [](const Scene& scene) {
    double weighted = 0.0, total = 0.0;
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
      const glm::vec3 rho =
          irad::hemispherical_albedo(irad::brdf_inputs_at(scene, t, glm::vec2(1.0f / 3.0f)));
      const double a = irad::triangle_area(scene, t);
      weighted += a * (rho.x + rho.y + rho.z) / 3.0;
      total += a;
    }
    return weighted / total;
  };
  ASSERT_GT(std::abs(expected(s) - (2 * 0.5 + 1 * 0.8 + 0.5 * 0.5) / 3.5), 0.01); // a metal
  EXPECT_NEAR(irad::mean_albedo(s), expected(s), 1e-6); // float albedos summed in double
  s.colors = {{1, 0.5, 0.5, 1},   {0.5, 1, 0.5, 1},   {0.5, 0.5, 1, 1},
              {0.2, 0.2, 0.2, 1}, {0.4, 0.4, 0.4, 1}, {0.6, 0.6, 0.6, 1},
              {1, 1, 1, 1},       {0, 0, 0, 1},       {0.1, 0.9, 0.3, 1}};
  EXPECT_NEAR(irad::mean_albedo(s), expected(s), 1e-6);
}

TEST(SceneModel, TexturedAlbedoAndEmissionInterpolateUvs) {
  Scene s = two_triangles();
  s.textures = {two_by_two(irad::Wrap::Repeat, irad::Wrap::Repeat)};
  s.materials[0].base_color_texture = 0;
  s.materials[1].emissive_texture = 0;
  // Without uvs the texture is not used.
  expect_near(irad::albedo_at(s, 0, {0.2f, 0.3f}), glm::vec3(0.5f));
  s.uvs = {{0.25f, 0.25f}, {0.75f, 0.25f}, {0.25f, 0.75f}, {0, 0}, {0, 0}, {0, 0}};
  const irad::Texture& t = s.textures[0];
  expect_near(irad::albedo_at(s, 0, {0, 0}), 0.5f * glm::vec3(t.texels[0]));
  expect_near(irad::albedo_at(s, 0, {1, 0}), 0.5f * glm::vec3(t.texels[1]));
  expect_near(irad::albedo_at(s, 0, {0, 1}), 0.5f * glm::vec3(t.texels[2]));
  expect_near(irad::albedo_at(s, 0, {0.5f, 0}), 0.25f * glm::vec3(t.texels[0] + t.texels[1]));
  expect_near(irad::emission_at(s, 1, {0.3f, 0.3f}), 3.0f * glm::vec3(t.sample({0, 0})));
  // Mean albedo takes the texture at its texel mean (0.5, 0.5, 0.5).
  EXPECT_NEAR(irad::mean_albedo(s), (2 * 0.25 + 1 * 0.8) / 3.0, 1e-6);
}

} // namespace IRAD_UNITY_ID
