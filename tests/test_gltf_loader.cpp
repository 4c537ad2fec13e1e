// Tests of the glTF loader, textures and the scene model. glTF files are written from C++ into a
// temporary directory: JSON through nlohmann::json, buffers as base64 data URIs, .bin files or GLB
// chunks, images as hand-written (stored-deflate) PNGs.
#include "core/gltf/loader.h"
#include "core/scene/scene.h"
#include "core/scene/texture.h"
#include "core/util/error.h"
#include "core/util/log.h"
#include "tests/gltf_loader_fixture.h"
#include "tests/gltf_test_scene.h"
#include "tests/test_paths.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <gtest/gtest.h>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <unistd.h>
#include <vector>

namespace IRAD_UNITY_ID {

using namespace gltf_test;
using irad::Scene;

TEST_F(GltfLoader, TrsQuadAndInverseTransposeNormals) {
  const float h = std::sqrt(0.5f); // rotation by 90 degrees about z: (x, y) -> (-y, x)
  Gltf g =
      emissive_quad({{"translation", {1, 2, 3}}, {"rotation", {0, 0, h, h}}, {"scale", {2, 3, 1}}});
  const glm::vec3 n = glm::normalize(glm::vec3(1, 1, 1));
  g.doc["meshes"][0]["primitives"][0] = quad_primitive(g, 0, std::vector<glm::vec3>(4, n));
  const Scene s = load(g.write_gltf(dir / "trs.gltf"));
  ASSERT_EQ(s.positions.size(), 4u);
  expect_near(s.positions[0], {1, 2, 3});
  expect_near(s.positions[1], {1, 4, 3});  // (1,0,0) -> scale (2,0,0) -> rotate (0,2,0) + t
  expect_near(s.positions[2], {-2, 4, 3}); // (1,1,0) -> (2,3,0) -> (-3,2,0) + t
  // Normals: R S^-1 n, renormalised: S^-1 n ~ (1/2, 1/3, 1) -> R -> (-1/3, 1/2, 1).
  const glm::vec3 expected = glm::normalize(glm::vec3(-1.0f / 3, 0.5f, 1));
  for (const glm::vec3& normal : s.normals) expect_near(normal, expected);
  expect_near(irad::geometric_normal(s, 0), {0, 0, 1});
  EXPECT_NEAR(irad::triangle_area(s, 0) + irad::triangle_area(s, 1), 6.0f, 1e-5f);
  expect_near(s.bounds.lo, {-2, 2, 3});
  expect_near(s.bounds.hi, {1, 4, 3});
}

TEST_F(GltfLoader, MirroringFlipsWindingToKeepFrontFace) {
  Gltf g = emissive_quad({{"scale", {-1, 1, 1}}});
  const Scene s = load(g.write_gltf(dir / "mirror.gltf"));
  for (std::size_t t = 0; t < s.triangle_count(); ++t) {
    expect_near(irad::geometric_normal(s, t), {0, 0, 1}); // mirrored in x: front stays +z
  }
  for (const glm::vec3& normal : s.normals) expect_near(normal, {0, 0, 1});
  expect_near(s.bounds.lo, {-1, 0, 0});
}

TEST_F(GltfLoader, HierarchyComposesParentTimesChild) {
  Gltf g = emissive_quad({{"translation", {1, 0, 0}}}); // nodes[0]: the quad
  // nodes[1] scales its child by 2; nodes[2] (a column-major matrix) translates by (0, 0, 5).
  g.push("nodes", {{"scale", {2, 2, 2}}, {"children", {0}}});
  g.push("nodes",
         {{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1}}, {"children", {1}}});
  g.doc["scenes"] = {{{"nodes", {2}}}};
  const Scene s = load(g.write_gltf(dir / "hierarchy.gltf"));
  expect_near(s.positions[0], {2, 0, 5}); // 2 * ((0,0,0) + (1,0,0)) + (0,0,5)
  expect_near(s.positions[2], {4, 2, 5}); // 2 * ((1,1,0) + (1,0,0)) + (0,0,5)
}

TEST_F(GltfLoader, NoScenesLoadsAllRootNodes) {
  Gltf g = emissive_quad();
  g.doc.erase("scenes");
  g.doc.erase("scene");
  g.push("nodes", {{"mesh", 0}, {"translation", {0, 0, 2}}});
  const Scene s = load(g.write_gltf(dir / "roots.gltf"));
  EXPECT_EQ(s.triangle_count(), 4u);
}

TEST_F(GltfLoader, IndexTypesAndNonIndexedGiveTheSameTriangles) {
  auto build = [&](const std::string& name, auto make_indices) {
    Gltf g = emissive_quad();
    json p = quad_primitive(g, 0, kUpNormals);
    make_indices(g, p);
    g.doc["meshes"][0]["primitives"][0] = p;
    return corners(load(g.write_gltf(dir / name)));
  };
  const auto u16 = build("u16.gltf", [](Gltf&, json&) {});
  const auto u8 = build("u8.gltf", [](Gltf& g, json& p) {
    p["indices"] = g.indices(std::vector<std::uint8_t>{0, 1, 2, 0, 2, 3});
  });
  const auto u32 = build("u32.gltf", [](Gltf& g, json& p) {
    p["indices"] = g.indices(std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3});
  });
  const auto plain = build("plain.gltf", [](Gltf& g, json& p) {
    p.erase("indices");
    std::vector<glm::vec3> soup;
    for (std::uint16_t i : kQuadIndices) soup.push_back(kQuad[i]);
    p["attributes"]["POSITION"] = g.vec3s(soup);
    p["attributes"]["NORMAL"] = g.vec3s(std::vector<glm::vec3>(6, glm::vec3(0, 0, 1)));
  });
  ASSERT_EQ(u16.size(), 6u);
  EXPECT_EQ(u8, u16);
  EXPECT_EQ(u32, u16);
  EXPECT_EQ(plain, u16);
}

TEST_F(GltfLoader, StripsAndFansBecomeFrontFacingTriangles) {
  for (int mode : {5, 6}) {
    Gltf g = emissive_quad();
    json p = quad_primitive(g, 0, kUpNormals);
    p["mode"] = mode; // strip 0 1 3 2, fan 0 1 2 3: both cover the quad counter-clockwise
    p["indices"] = mode == 5 ? g.indices(std::vector<std::uint16_t>{0, 1, 3, 2})
                             : g.indices(std::vector<std::uint16_t>{0, 1, 2, 3});
    g.doc["meshes"][0]["primitives"][0] = p;
    const Scene s = load(g.write_gltf(dir / ("mode" + std::to_string(mode) + ".gltf")));
    ASSERT_EQ(s.triangle_count(), 2u) << mode;
    for (std::size_t t = 0; t < 2; ++t) {
      expect_near(irad::geometric_normal(s, t), {0, 0, 1});
      EXPECT_NEAR(irad::triangle_area(s, t), 0.5f, 1e-6f);
    }
  }
}

TEST_F(GltfLoader, SparseAccessorOverridesElements) {
  Gltf g = emissive_quad();
  const std::vector<std::uint8_t> which{2};
  const std::vector<glm::vec3> values{{3, 3, 0}};
  const int base = g.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
  g.doc["accessors"][static_cast<std::size_t>(base)]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", g.view(which.data(), 1)}, {"componentType", kU8}}},
      {"values", {{"bufferView", g.view(values.data(), 12)}}}};
  g.doc["accessors"][static_cast<std::size_t>(base)]["max"] = {3, 3, 0}; // with the substitution
  const Scene s = load(g.write_gltf(dir / "sparse.gltf"));
  expect_near(s.positions[2], {3, 3, 0});
  expect_near(s.positions[1], {1, 0, 0});
}

TEST_F(GltfLoader, MissingNormalGivesFlatNormalsAndDegenerateTrianglesAreDropped) {
  Gltf g = emissive_quad();
  // A roof: triangle 0 1 2 in z = 0 (normal +z), triangle 0 3 1 in y = 0 (normal +y); then a
  // triangle with a repeated index and a collinear one.
  const std::vector<glm::vec3> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {2, 0, 0}};
  const json prim = {
      {"attributes", {{"POSITION", g.vec3s(p)}}},
      {"indices", g.indices(std::vector<std::uint8_t>{0, 1, 2, 0, 3, 1, 0, 0, 1, 0, 1, 4})},
      {"material", 0}};
  g.doc["meshes"][0]["primitives"][0] = prim;
  const Scene s = load(g.write_gltf(dir / "flat.gltf"));
  ASSERT_EQ(s.triangle_count(), 2u);
  EXPECT_EQ(s.positions.size(), 6u); // de-indexed: three vertices per triangle
  for (std::size_t t = 0; t < 2; ++t) {
    const glm::vec3 gn = irad::geometric_normal(s, t);
    for (unsigned v : {s.triangles[t].x, s.triangles[t].y, s.triangles[t].z}) {
      expect_near(s.normals[v], gn);
    }
  }
  expect_near(irad::geometric_normal(s, 0), {0, 0, 1});
  expect_near(irad::geometric_normal(s, 1), {0, 1, 0});
  EXPECT_EQ(warnings_containing("2 degenerate"), 1);
}

TEST_F(GltfLoader, ZeroNormalFallsBackToGeometricNormal) {
  Gltf g = emissive_quad();
  g.doc["meshes"][0]["primitives"][0] =
      quad_primitive(g, 0, {{0, 0, 0}, {0, 0, 1}, {kNaN, 0, 0}, {0, 0, 1}});
  const Scene s = load(g.write_gltf(dir / "zero_normal.gltf"));
  for (const glm::vec3& n : s.normals) expect_near(n, {0, 0, 1});
}

TEST_F(GltfLoader, MaterialFactorsEmissiveStrengthAndDoubleSided) {
  Gltf g = emissive_quad();
  g.doc["materials"][0] = {
      {"name", "lamp"},
      {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 0.125, 0.3}}}},
      {"emissiveFactor", {1.0, 0.5, 0.25}},
      {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}},
      {"doubleSided", true}};
  g.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  g.push("materials", {{"name", "plain"}});
  json& prims = g.doc["meshes"][0]["primitives"];
  prims.push_back(quad_primitive(g, 1, kUpNormals));
  prims.push_back(quad_primitive(g, -1, kUpNormals));
  const Scene s = load(g.write_gltf(dir / "materials.gltf"));
  ASSERT_EQ(s.materials.size(), 3u); // two from the file, then the default material
  const irad::Material& lamp = s.materials[0];
  EXPECT_EQ(lamp.name, "lamp");
  expect_near(lamp.base_color, {0.5f, 0.25f, 0.125f});
  expect_near(lamp.emission, {4, 2, 1});
  EXPECT_TRUE(lamp.double_sided);
  expect_near(s.materials[1].base_color, {1, 1, 1});
  EXPECT_FALSE(s.materials[1].emissive());
  EXPECT_FALSE(s.materials[1].double_sided);
  expect_near(s.materials[2].base_color, {1, 1, 1});
  EXPECT_FALSE(s.materials[2].emissive());
  ASSERT_EQ(s.triangle_count(), 6u);
  EXPECT_EQ(s.triangle_material, (std::vector<std::uint32_t>{0, 0, 1, 1, 2, 2}));
  EXPECT_TRUE(s.has_emitters());
  EXPECT_TRUE(s.uvs.empty());
}

// 2x2 RGB texture, top row (0, 64, 255) (128, 128, 128), bottom row (255, 0, 0) (32, 200, 16).
const std::vector<std::uint16_t> kTexels{0, 64, 255, 128, 128, 128, 255, 0, 0, 32, 200, 16};

glm::vec4 decoded(std::size_t texel) {
  auto c = [&](std::size_t k) {
    return irad::srgb_to_linear(float(kTexels[3 * texel + k]) / 255.0f);
  };
  return {c(0), c(1), c(2), 1.0f};
}

// The quad with TEXCOORD_0 (normalized u8) and a base-colour texture (sampler clamp/mirror);
// the emissive texture is a 16-bit grey+alpha image.
Gltf textured_quad() {
  Gltf g = emissive_quad();
  const std::vector<std::uint8_t> uv{0, 0, 255, 0, 255, 255, 0, 255};
  json p = quad_primitive(g, 0, kUpNormals);
  p["attributes"]["TEXCOORD_0"] =
      g.accessor(g.view(uv.data(), uv.size()), kU8, 4, "VEC2", {{"normalized", true}});
  g.doc["meshes"][0]["primitives"][0] = p;
  g.image_png(png(2, 2, 3, 8, kTexels));
  g.image_png(png(1, 1, 2, 16, {32768, 65535}));
  g.push("samplers", {{"wrapS", 33071}, {"wrapT", 33648}});
  g.push("textures", {{"source", 0}, {"sampler", 0}});
  g.push("textures", {{"source", 1}});
  g.doc["materials"][0] = {
      {"pbrMetallicRoughness",
       {{"baseColorFactor", {0.5, 1.0, 1.0, 1.0}}, {"baseColorTexture", {{"index", 0}}}}},
      {"emissiveFactor", {1.0, 1.0, 1.0}}, // x emissiveStrength 2
      {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 2.0}}}}},
      {"emissiveTexture", {{"index", 1}}}};
  g.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  // A second material sharing textures[0]: no second decoded copy (GlbLoadsTheSameAsGltf uses it).
  g.push("materials", {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
  return g;
}

TEST_F(GltfLoader, SrgbTextureDecodesToLinearAndIsSampledBilinearly) {
  const Scene s = load(textured_quad().write_gltf(dir / "texture.gltf"));
  ASSERT_EQ(s.textures.size(), 2u);
  const irad::Texture& t = s.textures[0];
  ASSERT_EQ(t.width, 2);
  ASSERT_EQ(t.height, 2);
  for (std::size_t i = 0; i < 4; ++i) expect_near(t.texels[i], decoded(i));
  EXPECT_EQ(t.wrap_s, irad::Wrap::ClampToEdge);
  EXPECT_EQ(t.wrap_t, irad::Wrap::MirroredRepeat);
  // 16-bit grey + alpha: grey replicated to RGB and sRGB-decoded, alpha linear.
  const float grey = irad::srgb_to_linear(32768.0f / 65535.0f);
  expect_near(s.textures[1].texels[0], {grey, grey, grey, 1.0f});
  ASSERT_EQ(s.uvs.size(), 4u);
  // At vertex 0 (uv 0,0) clamp and mirror both give texel (0, 0) alone; factor (0.5, 1, 1).
  expect_near(irad::albedo_at(s, 0, {0, 0}), glm::vec3(decoded(0)) * glm::vec3(0.5f, 1, 1));
  // Centre of the quad (uv 0.5, 0.5): the mean of the four texels.
  const glm::vec3 centre = irad::albedo_at(s, 0, {0.0f, 0.5f}); // midpoint of vertices 0 and 2
  const glm::vec4 mean = (decoded(0) + decoded(1) + decoded(2) + decoded(3)) / 4.0f;
  expect_near(centre, glm::vec3(mean) * glm::vec3(0.5f, 1, 1));
  expect_near(irad::emission_at(s, 0, {0.3f, 0.3f}), glm::vec3(2 * grey));
}

TEST_F(GltfLoader, PointSpotAndDirectionalLightsFromNodeExtensions) {
  Gltf g = emissive_quad();
  g.doc["materials"][0] = json::object(); // lit only by the punctual lights
  g.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  g.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "point"},
       {"name", "bulb"},
       {"color", {1.0, 0.5, 0.25}},
       {"intensity", 8.0},
       {"range", 10.0}},
      {{"type", "spot"},
       {"intensity", 2.0},
       {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.5}}}},
      {{"type", "directional"}, {"intensity", 3.0}}};
  const float h = std::sqrt(0.5f); // 90 degrees about x: -z -> +y
  auto light = [](int i) { return json{{"KHR_lights_punctual", {{"light", i}}}}; };
  g.push("nodes", {{"translation", {1, 2, 3}}, {"extensions", light(0)}});
  g.push("nodes",
         {{"rotation", {h, 0, 0, h}}, {"translation", {0, 0, 4}}, {"extensions", light(1)}});
  g.push("nodes", {{"rotation", {h, 0, 0, h}}, {"extensions", light(2)}});
  g.doc["scenes"][0]["nodes"] = {0, 1, 2, 3};
  const Scene s = load(g.write_gltf(dir / "lights.gltf"));
  ASSERT_EQ(s.lights.size(), 3u);
  const irad::PunctualLight& point = s.lights[0];
  EXPECT_EQ(point.name, "bulb");
  EXPECT_EQ(point.kind, irad::PunctualLight::Kind::Point);
  expect_near(point.position, {1, 2, 3});
  expect_near(point.intensity, {8, 4, 2});
  const irad::PunctualLight& spot = s.lights[1];
  EXPECT_EQ(spot.kind, irad::PunctualLight::Kind::Spot);
  EXPECT_EQ(spot.name, "light1");
  expect_near(spot.position, {0, 0, 4});
  expect_near(spot.direction, {0, 1, 0});
  expect_near(spot.intensity, {2, 2, 2});
  EXPECT_NEAR(spot.inner_cone, 0.2f, 1e-7f);
  EXPECT_NEAR(spot.outer_cone, 0.5f, 1e-7f);
  const irad::PunctualLight& sun = s.lights[2];
  EXPECT_EQ(sun.kind, irad::PunctualLight::Kind::Directional);
  expect_near(sun.direction, {0, 1, 0}); // the node's -z
  expect_near(sun.intensity, {3, 3, 3}); // irradiance
  EXPECT_EQ(warnings_containing("range"), 1);
}

TEST_F(GltfLoader, CameraIsReadAndScaleRemoved) {
  Gltf g = emissive_quad();
  g.push("cameras",
         {{"type", "perspective"},
          {"perspective", {{"yfov", 0.8}, {"aspectRatio", 1.5}, {"znear", 0.1}, {"zfar", 100.0}}}});
  g.push("nodes", {{"camera", 0}, {"translation", {0, 0, 10}}, {"scale", {2, 3, 4}}});
  g.push("cameras",
         {{"type", "orthographic"},
          {"orthographic", {{"xmag", 2.0}, {"ymag", 0.5}, {"znear", 0.1}, {"zfar", 9.0}}}});
  g.push("nodes", {{"camera", 1}, {"translation", {0, 1, 5}}});
  g.doc["scenes"][0]["nodes"] = {0, 1, 2};
  const Scene s = load(g.write_gltf(dir / "camera.gltf"));
  ASSERT_EQ(s.cameras.size(), 2u); // the orthographic camera is loaded too
  const irad::Camera& c = s.cameras[0];
  EXPECT_EQ(c.name, "camera0");
  EXPECT_FALSE(c.orthographic);
  EXPECT_NEAR(c.yfov, 0.8f, 1e-7f);
  ASSERT_TRUE(c.aspect.has_value());
  EXPECT_NEAR(*c.aspect, 1.5f, 1e-7f);
  EXPECT_NEAR(c.znear, 0.1f, 1e-7f);
  ASSERT_TRUE(c.zfar.has_value());
  EXPECT_NEAR(*c.zfar, 100.0f, 1e-5f);
  expect_near(c.position(), {0, 0, 10});
  for (int k = 0; k < 3; ++k) {
    expect_near(glm::vec3(c.camera_to_world[k]), glm::vec3(glm::mat3(1.0f)[k]));
  }
  const irad::Camera& o = s.cameras[1];
  EXPECT_TRUE(o.orthographic);
  EXPECT_NEAR(o.xmag, 2.0f, 1e-7f);
  EXPECT_NEAR(o.ymag, 0.5f, 1e-7f);
  EXPECT_NEAR(o.znear, 0.1f, 1e-7f);
  ASSERT_TRUE(o.zfar.has_value());
  EXPECT_NEAR(*o.zfar, 9.0f, 1e-6f);
  expect_near(o.position(), {0, 1, 5});
  EXPECT_TRUE(warnings.empty()) << ::testing::PrintToString(warnings);
}

TEST_F(GltfLoader, PointsAndLinesAreSkippedWithOneWarning) {
  Gltf g = emissive_quad();
  for (int mode : {0, 1, 3}) {
    json p = quad_primitive(g, 0, kUpNormals);
    p["mode"] = mode;
    g.doc["meshes"][0]["primitives"].push_back(p);
  }
  const Scene s = load(g.write_gltf(dir / "points.gltf"));
  EXPECT_EQ(s.triangle_count(), 2u);
  EXPECT_EQ(warnings.size(), 1u) << ::testing::PrintToString(warnings);
  EXPECT_EQ(warnings_containing("point and line primitives are not supported"), 1);
}

TEST_F(GltfLoader, DefaultCameraFramesTheBoundsWhenAbsent) {
  const Scene s = load(emissive_quad().write_gltf(dir / "nocamera.gltf"));
  ASSERT_EQ(s.cameras.size(), 1u);
  const irad::Camera& c = s.cameras[0];
  EXPECT_EQ(c.name, "default");
  EXPECT_FALSE(c.aspect.has_value());
  EXPECT_NEAR(c.yfov, 0.6911f, 1e-6f);
  const float distance = 0.5f * std::sqrt(2.0f) / std::sin(0.5f * 0.6911f);
  expect_near(c.position(), {0.5f, 0.5f, distance});
  expect_near(glm::vec3(c.camera_to_world[2]), {0, 0, 1}); // looks down -z
}

TEST_F(GltfLoader, GlbLoadsTheSameAsGltf) {
  Gltf g = textured_quad();
  g.doc["meshes"][0]["primitives"].push_back(quad_primitive(g, 1, {}));
  const Scene a = load(g.write_gltf(dir / "scene.gltf"));
  const Scene b = load(g.write_glb(dir / "scene.glb"));
  const Scene c = load(g.write_gltf_bin(dir / "external.gltf"));
  ASSERT_EQ(a.materials.size(), 2u);
  EXPECT_EQ(a.materials[1].base_color_texture, a.materials[0].base_color_texture);
  for (const Scene* other : {&b, &c}) {
    EXPECT_EQ(corners(*other), corners(a));
    EXPECT_EQ(other->normals, a.normals);
    EXPECT_EQ(other->uvs, a.uvs);
    EXPECT_EQ(other->triangle_material, a.triangle_material);
    ASSERT_EQ(other->textures.size(), a.textures.size());
    EXPECT_EQ(other->textures[0].texels, a.textures[0].texels);
    ASSERT_EQ(other->materials.size(), a.materials.size());
    EXPECT_EQ(other->materials[0].emission, a.materials[0].emission);
  }
}

// A GLB chunk of another type after JSON and BIN is skipped (glTF 2.0, 4.4.3.1: clients must
// ignore chunks of unknown types).
TEST_F(GltfLoader, GlbChunkOfUnknownTypeIsSkipped) {
  Gltf g = emissive_quad();
  const fs::path path = g.write_glb(dir / "extra.glb");
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in), {}};
  in.close();
  put_le32(bytes, 4);
  bytes.insert(bytes.end(), {'X', 'T', 'R', 'A', 1, 2, 3, 4});
  const std::uint32_t length = static_cast<std::uint32_t>(bytes.size());
  std::memcpy(bytes.data() + 8, &length, 4); // little-endian hosts only, as irad
  write_file(path, bytes.data(), bytes.size());
  const Scene s = load(path);
  EXPECT_EQ(corners(s), corners(load(g.write_gltf(dir / "extra.gltf"))));
}

// A buffer without uri outside a GLB reads as zeros, with a warning naming it: here the quad's
// normals, which then fall back to the geometric normal.
TEST_F(GltfLoader, BufferWithoutUriInGltfReadsAsZerosWithAWarning) {
  Gltf g = emissive_quad();
  const fs::path path = g.write_gltf(dir / "nouri.gltf");
  json doc = json::parse(std::ifstream(path));
  doc["buffers"].push_back({{"byteLength", 48}});
  doc["bufferViews"].push_back({{"buffer", 1}, {"byteLength", 48}});
  doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1},
                              {"componentType", kFloat},
                              {"count", 4},
                              {"type", "VEC3"}});
  doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = doc["accessors"].size() - 1;
  write_file(path, doc.dump());
  const Scene s = load(path);
  ASSERT_EQ(s.triangle_count(), 2u);
  for (const glm::vec3& n : s.normals) expect_near(n, {0, 0, 1});
  EXPECT_EQ(warnings_containing("buffers[1]: no uri and no data; its bytes are read as zeros"), 1)
      << ::testing::PrintToString(warnings);
}

// ---------------------------------------------------------------------------------------------
// Bad inputs: each gives one irad::Error naming the file and the element.

TEST_F(GltfLoader, MissingFile) {
  expect_error(dir / "missing.gltf", "", "cannot open file");
}

TEST_F(GltfLoader, BrokenJson) {
  write_file(dir / "broken.gltf", "{ \"asset\": { \"version\": \"2.0\" }, \n \"nodes\": [ {,, ]");
  expect_error(dir / "broken.gltf", "", "");
}

TEST_F(GltfLoader, Version1IsRejected) {
  Gltf g = emissive_quad();
  g.doc["asset"]["version"] = "1.0";
  expect_error(g.write_gltf(dir / "v1.gltf"), "asset.version", "unsupported glTF version '1.0'");
}

TEST_F(GltfLoader, NanAndInfVerticesDropTheirTrianglesWithOneWarning) {
  // Vertex 1 is NaN: triangle 012 goes, 023 stays. A second primitive with an Inf vertex loses
  // its triangles too; one warning counts them all.
  Gltf g = emissive_quad();
  const float inf = std::numeric_limits<float>::infinity();
  auto& prims = g.doc["meshes"][0]["primitives"];
  prims[0]["attributes"]["POSITION"] = g.positions({{0, 0, 0}, {1, kNaN, 0}, {1, 1, 0}, {0, 1, 0}});
  json second = quad_primitive(g, 0, kUpNormals);
  second["attributes"]["POSITION"] = g.positions({{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, inf, 1}});
  prims.push_back(second);
  const Scene s = load(g.write_gltf(dir / "nan.gltf"));
  EXPECT_EQ(corners(s), (std::vector<glm::vec3>{
                            {0, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}}));
  // The validator's ACCESSOR_INVALID_FLOAT, repaired, is one warning per accessor; the dropped
  // triangles are one warning for the file.
  ASSERT_EQ(warnings.size(), 3u) << ::testing::PrintToString(warnings);
  EXPECT_EQ(warnings_containing("accessors[3]: component 4 is NaN or infinite; triangles with a "
                                "NaN or Inf vertex are dropped"),
            1);
  EXPECT_EQ(warnings_containing("accessors[7]: component 10 is NaN or infinite"), 1);
  EXPECT_EQ(warnings_containing("nan.gltf: 2 triangle(s) with a NaN or Inf vertex position "
                                "dropped (the first in meshes[0].primitives[0])"),
            1);
  // Every vertex non-finite: nothing is left, which is the error "no triangles".
  Gltf all = emissive_quad();
  all.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] =
      all.vec3s(std::vector<glm::vec3>(4, glm::vec3(kNaN)));
  expect_error(all.write_gltf(dir / "all_nan.gltf"), "", "no triangles");
}

TEST_F(GltfLoader, GlbWithBadMagic) {
  expect_error(emissive_quad().write_glb(dir / "magic.glb", "glTX"), "", "magic");
}

TEST_F(GltfLoader, BufferShorterThanByteLength) {
  Gltf g = emissive_quad();
  const fs::path path = g.write_gltf(dir / "short.gltf");
  json doc = json::parse(std::ifstream(path));
  doc["buffers"][0]["byteLength"] = g.bin.size() + 16;
  write_file(path, doc.dump());
  expect_error(path, "buffers[0]", "its data hold 108 bytes, byteLength says 124");

  const fs::path external = g.write_gltf_bin(dir / "short_bin.gltf");
  fs::resize_file(fs::path(external).replace_extension(".bin"), g.bin.size() - 8);
  expect_error(external, "buffers[0]", "its data hold 100 bytes, byteLength says 108");
}

TEST_F(GltfLoader, CornellBox) {
  const fs::path path = fs::path(IRAD_SOURCE_DIR) / "data" / "cornell_box.gltf";
  if (!fs::exists(path)) GTEST_SKIP() << path << " not generated yet";
  const Scene s = load(path);
  // data/make_cornell_box.py: five walls (10), two blocks without bottom faces (2 x 10), the
  // light (2); no triangle may be dropped.
  EXPECT_EQ(s.triangle_count(), 32u);
  EXPECT_TRUE(warnings.empty());
  int lights = 0;
  for (const irad::Material& m : s.materials) {
    if (!m.emissive()) continue;
    ++lights;
    expect_near(m.emission, {17, 12, 4});
  }
  EXPECT_EQ(lights, 1);
  EXPECT_GT(irad::mean_albedo(s), 0.4);
  EXPECT_LT(irad::mean_albedo(s), 0.8);
  // The published camera looks down +z from z = -0.8 m: its local +z axis is world -z.
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_NEAR(s.cameras[0].yfov, 2.0f * std::atan(12.5f / 35.0f), 1e-5f);
  expect_near(glm::vec3(s.cameras[0].camera_to_world[2]), {0, 0, -1});
  expect_near(s.cameras[0].position(), {0.278f, 0.273f, -0.8f});
}

} // namespace
