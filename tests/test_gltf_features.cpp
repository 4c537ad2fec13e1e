// The glTF features real assets use, each against an exact answer computed here by hand: skins
// (at rest and animated) against the mesh posed by hand, morph targets (default, node and
// animated weights), KHR_texture_transform and texCoord sets, COLOR_0, KHR_mesh_quantization,
// sparse accessors without a bufferView, Draco and meshopt compressed primitives against the
// uncompressed mesh, EXT_texture_webp, orthographic cameras, choosing a scene, and the rules for
// extensions and for problems in unused parts and in extensions irad ignores.
#include "core/animation/animation.h"
#include "core/gltf/loader.h"
#include "core/scene/scene.h"
#include "core/util/error.h"
#include "core/util/log.h"
#include "tests/compressed_fixtures.h"
#include "tests/gltf_test_scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <webp/encode.h>

namespace IRAD_UNITY_ID {

using namespace gltf_test;
using irad::Scene;

class GltfFeatures : public ::testing::Test {
protected:
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("irad_features_" +
           std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  Scene load(const fs::path& path, const std::string& scene = {}) {
    irad::Log log([this](const std::string& m) { warnings.push_back(m); });
    return irad::load_gltf(path, log, {}, scene);
  }
  bool warned(const std::string& fragment) const {
    return std::any_of(warnings.begin(), warnings.end(),
                       [&](const std::string& w) { return w.find(fragment) != std::string::npos; });
  }

  fs::path dir;
  std::vector<std::string> warnings;
};

// One animation with one sampler (input, output) and one channel targeting node.path.
json one_channel(int input, int output, int node, const char* path) {
  json sampler = {{"input", input}, {"output", output}};
  json channel = {{"sampler", 0}, {"target", {{"node", node}, {"path", path}}}};
  return {{"samplers", json::array({sampler})}, {"channels", json::array({channel})}};
}

// The quad skinned to two joints (nodes 1 and 2): vertices 0 and 1 follow joint 0, vertex 2
// joint 1, vertex 3 both (weights 0.75 and 0.25; at 0.5 each it would lie on the diagonal at
// rest, a degenerate triangle the loader drops). Joint 1 is translated by (0, 0, 2) and turned 90
// degrees about z.
constexpr float kH = 0.70710678f;

Gltf skinned_quad(bool with_ibm) {
  Gltf g = emissive_quad({{"skin", 0}});
  const std::vector<std::uint8_t> joints{0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0};
  const std::vector<float> weights{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0.75f, 0.25f, 0, 0};
  auto& attrs = g.doc["meshes"][0]["primitives"][0]["attributes"];
  attrs["JOINTS_0"] = g.accessor(g.view(joints.data(), joints.size()), kU8, 4, "VEC4");
  attrs["WEIGHTS_0"] = g.accessor(g.view(weights.data(), weights.size() * 4), kFloat, 4, "VEC4");
  // Joint 0 (node 1, the skeleton's root at the origin) is joint 1's (node 2's) parent.
  g.push("nodes", {{"translation", {0, 0, 0}}, {"children", {2}}});
  g.push("nodes", {{"translation", {0, 0, 2}}, {"rotation", {0, 0, kH, kH}}});
  json skin = {{"joints", {1, 2}}};
  if (with_ibm) {
    // Joint 1's inverse bind matrix undoes a bind translation of (1, 0, 0).
    glm::mat4 ibm[2] = {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), {-1, 0, 0})};
    skin["inverseBindMatrices"] = g.accessor(g.view(ibm, sizeof ibm), kFloat, 2, "MAT4");
  }
  g.push("skins", skin);
  g.doc["scenes"][0]["nodes"] = {0, 1};
  return g;
}

// The skinned positions by hand: p' = sum_k w_k J_k B_k p.
std::vector<glm::vec3> skin_by_hand(const glm::mat4& j1, const glm::mat4& b1) {
  const glm::mat4 m0(1.0f), m1 = j1 * b1;
  std::vector<glm::vec3> out;
  const float w1[4] = {0, 0, 1, 0.25f};
  for (int v = 0; v < 4; ++v) {
    const glm::vec4 p(kQuad[std::size_t(v)], 1.0f);
    out.push_back(glm::vec3((1.0f - w1[v]) * (m0 * p) + w1[v] * (m1 * p)));
  }
  return out;
}

glm::mat4 joint1(float angle) {
  return glm::translate(glm::mat4(1.0f), {0, 0, 2}) *
         glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0, 0, 1));
}

// Scene vertex positions in file order (the quad's four vertices, none dropped).
std::vector<glm::vec3> quad_positions(const Scene& s) {
  return {s.positions.begin(), s.positions.begin() + 4};
}

void expect_positions(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b,
                      float tol = 1e-5f) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE(i);
    expect_near(a[i], b[i], tol);
  }
}

TEST_F(GltfFeatures, SkinAtRestEqualsTheMeshPosedByHand) {
  const float quarter = 1.5707963f;
  const Scene without = load(skinned_quad(false).write_gltf(dir / "skin.gltf"));
  expect_positions(quad_positions(without), skin_by_hand(joint1(quarter), glm::mat4(1.0f)));
  const Scene with = load(skinned_quad(true).write_gltf(dir / "skin_ibm.gltf"));
  expect_positions(quad_positions(with),
                   skin_by_hand(joint1(quarter), glm::translate(glm::mat4(1.0f), {-1, 0, 0})));
}

TEST_F(GltfFeatures, AnimatedSkinFollowsItsJointAtEveryTime) {
  Gltf g = skinned_quad(false);
  // Joint 1 (node 2) turns from 0 to 90 degrees about z over one second.
  const std::vector<float> times{0, 1};
  const std::vector<float> quats{0, 0, 0, 1, 0, 0, kH, kH};
  const int t =
      g.accessor(g.view(times.data(), 8), kFloat, 2, "SCALAR", {{"min", {0.0}}, {"max", {1.0}}});
  const int q = g.accessor(g.view(quats.data(), 32), kFloat, 2, "VEC4");
  g.doc["animations"] = json::array({one_channel(t, q, 2, "rotation")});
  Scene s = load(g.write_gltf(dir / "skin_anim.gltf"));
  ASSERT_TRUE(s.animation && s.animation->moves_geometry());
  for (float time : {0.0f, 0.5f, 1.0f}) {
    SCOPED_TRACE(time);
    s.animation->pose(time, s);
    // Slerp between 0 and 90 degrees: the angle is linear in time.
    expect_positions(quad_positions(s), skin_by_hand(joint1(1.5707963f * time), glm::mat4(1.0f)),
                     2e-5f);
  }
}

// The quad with one morph target moving vertex 2 by (0, 0, 1) and vertex 3 by (0, 0, 2).
Gltf morphed_quad() {
  Gltf g = emissive_quad();
  const std::vector<glm::vec3> d{{0, 0, 0}, {0, 0, 0}, {0, 0, 1}, {0, 0, 2}};
  g.doc["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", g.positions(d)}}};
  g.doc["meshes"][0]["weights"] = {0.25};
  return g;
}

std::vector<glm::vec3> morph_by_hand(float w) {
  std::vector<glm::vec3> out = kQuad;
  out[2].z += w;
  out[3].z += 2 * w;
  return out;
}

TEST_F(GltfFeatures, MorphTargetsTakeTheMeshThenTheNodeWeights) {
  expect_positions(quad_positions(load(morphed_quad().write_gltf(dir / "m.gltf"))),
                   morph_by_hand(0.25f));
  Gltf g = morphed_quad();
  g.doc["nodes"][0]["weights"] = {0.75};
  expect_positions(quad_positions(load(g.write_gltf(dir / "n.gltf"))), morph_by_hand(0.75f));
}

TEST_F(GltfFeatures, AnimatedMorphWeightsInterpolate) {
  Gltf g = morphed_quad();
  const std::vector<float> times{0, 2};
  const std::vector<float> w{0, 1};
  const int t =
      g.accessor(g.view(times.data(), 8), kFloat, 2, "SCALAR", {{"min", {0.0}}, {"max", {2.0}}});
  const int v = g.accessor(g.view(w.data(), 8), kFloat, 2, "SCALAR");
  g.doc["animations"] = json::array({one_channel(t, v, 0, "weights")});
  Scene s = load(g.write_gltf(dir / "wanim.gltf"));
  ASSERT_TRUE(s.animation && s.animation->moves_geometry());
  for (float time : {0.0f, 0.5f, 2.0f}) {
    SCOPED_TRACE(time);
    s.animation->pose(time, s);
    expect_positions(quad_positions(s), morph_by_hand(time / 2.0f));
  }
  // The bounds cover the whole animation (vertex 3 reaches z = 2).
  EXPECT_NEAR(s.bounds.hi.z, 2.0f, 1e-5f);
}

TEST_F(GltfFeatures, TextureTransformAndTexCoordSets) {
  Gltf g = emissive_quad();
  const std::vector<glm::vec2> uv0{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<glm::vec2> uv2{{0.5f, 0}, {0.5f, 0.5f}, {0, 0.5f}, {0, 0}};
  auto& attrs = g.doc["meshes"][0]["primitives"][0]["attributes"];
  attrs["TEXCOORD_0"] = g.vec2s(uv0);
  attrs["TEXCOORD_1"] = g.vec2s(uv0);
  attrs["TEXCOORD_2"] = g.vec2s(uv2);
  g.image_png(png(1, 1, 3, 8, {255, 255, 255}));
  g.push("textures", {{"source", 0}});
  g.doc["extensionsUsed"] = {"KHR_texture_transform"};
  g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {
      {"index", 0},
      {"extensions",
       {{"KHR_texture_transform",
         {{"offset", {0.5, 0.25}}, {"rotation", 1.5707963}, {"scale", {2.0, 3.0}}}}}}};
  g.doc["materials"][0]["emissiveTexture"] = {{"index", 0}, {"texCoord", 2}};
  const Scene s = load(g.write_gltf(dir / "tt.gltf"));
  const irad::Material& m = s.materials[0];
  // Base colour reads TEXCOORD_0 (slot 0) through T R S; the emissive texture TEXCOORD_2 (slot 1).
  EXPECT_EQ(m.base_color_map.texcoord, 0);
  EXPECT_EQ(m.emissive_map.texcoord, 1);
  ASSERT_EQ(s.uvs1.size(), s.uvs.size());
  expect_near(glm::vec3(s.uvs1[1], 0), glm::vec3(uv2[1], 0));
  // The extension's formula for uv (1, 1): scale (2, 3), rotate by -90 degrees in its
  // convention (x' = cos x + sin y, y' = -sin x + cos y), then offset.
  const glm::vec2 scaled(2.0f, 3.0f);
  const glm::vec2 rotated(scaled.y, -scaled.x);
  const glm::vec2 expected = rotated + glm::vec2(0.5f, 0.25f);
  const glm::vec2 got = m.base_color_map.apply({1, 1});
  EXPECT_NEAR(got.x, expected.x, 1e-5f);
  EXPECT_NEAR(got.y, expected.y, 1e-5f);
}

TEST_F(GltfFeatures, VertexColoursAreRead) {
  Gltf g = emissive_quad();
  const std::vector<std::uint8_t> rgba{255, 0, 0,   255, 0,   255, 0,   128,
                                       0,   0, 255, 255, 255, 255, 255, 0};
  g.doc["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] =
      g.accessor(g.view(rgba.data(), rgba.size()), kU8, 4, "VEC4", {{"normalized", true}});
  const Scene s = load(g.write_gltf(dir / "c.gltf"));
  ASSERT_EQ(s.colors.size(), s.positions.size());
  expect_near(s.colors[1], {0, 1, 0, 128.0f / 255.0f});
}

TEST_F(GltfFeatures, QuantizedPositionsAndSparseAccessorsWithoutBufferView) {
  Gltf g = emissive_quad({{"scale", {0.5, 0.5, 0.5}}});
  const std::vector<std::int16_t> p{0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0};
  g.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
  g.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  g.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] =
      g.accessor(g.view(p.data(), 24), 5122, 4, "VEC3", {{"min", {0, 0, 0}}, {"max", {2, 2, 0}}});
  g.doc["meshes"][0]["primitives"][0]["attributes"].erase("NORMAL");
  const Scene s = load(g.write_gltf(dir / "q.gltf"));
  // Flat normals de-index the quad: triangle 0 is vertices (0, 1, 2) of the file, halved.
  expect_near(s.positions[1], {1, 0, 0});
  expect_near(s.positions[2], {1, 1, 0});

  // A sparse accessor without bufferView: zeros except the substituted elements.
  Gltf h = emissive_quad();
  const std::vector<std::uint8_t> which{1, 2, 3, 0};
  const std::vector<glm::vec3> values{{1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  h.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] =
      h.push("accessors",
             {{"componentType", kFloat},
              {"count", 4},
              {"type", "VEC3"},
              {"min", {0, 0, 0}},
              {"max", {1, 1, 0}},
              {"sparse",
               {{"count", 3},
                {"indices", {{"bufferView", h.view(which.data(), 4)}, {"componentType", kU8}}},
                {"values", {{"bufferView", h.view(values.data(), 36)}}}}}});
  expect_positions(quad_positions(load(h.write_gltf(dir / "sparse.gltf"))), kQuad);
}

// The Draco cube and the same cube uncompressed give the same triangles (as sets of corners,
// within half a quantization step of the cube's side 2 at 14 bits: 2 / 2^14 / 2 = 6.1e-5).
std::vector<std::vector<glm::vec3>> triangle_set(const Scene& s) {
  std::vector<std::vector<glm::vec3>> out;
  for (const glm::uvec3& t : s.triangles)
    out.push_back({s.positions[t.x], s.positions[t.y], s.positions[t.z]});
  return out;
}

bool close(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b, float tol) {
  for (int rot = 0; rot < 3; ++rot) {
    bool all = true;
    for (int k = 0; k < 3; ++k)
      all = all && glm::length(a[std::size_t(k)] - b[std::size_t((k + rot) % 3)]) <= tol;
    if (all) return true;
  }
  return false;
}

void expect_same_triangles(const Scene& a, const Scene& b, float tol) {
  const auto ta = triangle_set(a), tb = triangle_set(b);
  ASSERT_EQ(ta.size(), tb.size());
  for (const auto& t : ta)
    EXPECT_TRUE(std::any_of(tb.begin(), tb.end(), [&](const auto& u) { return close(t, u, tol); }));
}

Gltf cube_gltf(const irad::test::FixtureMesh& m) {
  Gltf g;
  g.push("materials", {{"emissiveFactor", {1.0, 1.0, 1.0}}});
  std::vector<glm::vec3> p(m.vertex_count()), n(m.vertex_count());
  std::memcpy(p.data(), m.positions.data(), m.positions.size() * 4);
  std::memcpy(n.data(), m.normals.data(), m.normals.size() * 4);
  json prim = {{"attributes", {{"POSITION", g.positions(p)}, {"NORMAL", g.vec3s(n)}}},
               {"indices", g.indices(m.indices)},
               {"material", 0}};
  g.push("meshes", {{"primitives", json::array({prim})}});
  g.push("nodes", {{"mesh", 0}});
  g.doc["scenes"] = {{{"nodes", {0}}}};
  return g;
}

TEST_F(GltfFeatures, DracoPrimitiveEqualsTheUncompressedMesh) {
  const irad::test::FixtureMesh m = irad::test::cube_mesh();
  const Scene plain = load(cube_gltf(m).write_gltf(dir / "plain.gltf"));
  const irad::test::DracoFixture d = irad::test::draco_encode(m, 14);
  Gltf g = cube_gltf(m);
  const int view = g.view(d.bytes.data(), d.bytes.size());
  auto& prim = g.doc["meshes"][0]["primitives"][0];
  // The accessors of a Draco primitive have no bufferView.
  for (const char* name : {"POSITION", "NORMAL"})
    g.doc["accessors"][prim["attributes"][name].get<int>()].erase("bufferView");
  g.doc["accessors"][prim["indices"].get<int>()].erase("bufferView");
  prim["extensions"] = {{"KHR_draco_mesh_compression",
                         {{"bufferView", view},
                          {"attributes", {{"POSITION", d.position_id}, {"NORMAL", d.normal_id}}}}}};
  g.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  g.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  expect_same_triangles(load(g.write_gltf(dir / "draco.gltf")), plain, 6.2e-5f);
}

TEST_F(GltfFeatures, MeshoptBufferViewsEqualTheUncompressedMesh) {
  const irad::test::FixtureMesh m = irad::test::cube_mesh();
  const Scene plain = load(cube_gltf(m).write_gltf(dir / "plain.gltf"));
  Gltf g = cube_gltf(m);
  // Each bufferView of the mesh gets an EXT_meshopt_compression twin in a second buffer; the
  // first buffer stays as the fallback.
  std::vector<unsigned char> packed;
  json& views = g.doc["bufferViews"];
  const std::size_t n = m.vertex_count();
  auto compress = [&](int v, const std::vector<unsigned char>& bytes, std::size_t count,
                      std::size_t stride, const char* mode) {
    while (packed.size() % 4) packed.push_back(0);
    views[v]["extensions"]["EXT_meshopt_compression"] = {{"buffer", 1},
                                                         {"byteOffset", packed.size()},
                                                         {"byteLength", bytes.size()},
                                                         {"byteStride", stride},
                                                         {"count", count},
                                                         {"mode", mode}};
    packed.insert(packed.end(), bytes.begin(), bytes.end());
  };
  const auto& acc = g.doc["accessors"];
  const auto& prim = g.doc["meshes"][0]["primitives"][0];
  const int pos_view = acc[prim["attributes"]["POSITION"].get<int>()]["bufferView"];
  const int nor_view = acc[prim["attributes"]["NORMAL"].get<int>()]["bufferView"];
  const int idx_view = acc[prim["indices"].get<int>()]["bufferView"];
  compress(pos_view, irad::test::meshopt_encode_vertices(m.positions.data(), n, 12), n, 12,
           "ATTRIBUTES");
  compress(nor_view, irad::test::meshopt_encode_vertices(m.normals.data(), n, 12), n, 12,
           "ATTRIBUTES");
  compress(idx_view, irad::test::meshopt_encode_triangles(m.indices, n), m.indices.size(), 4,
           "TRIANGLES");
  g.doc["extensionsUsed"] = {"EXT_meshopt_compression"};
  fs::path path = g.write_gltf(dir / "meshopt.gltf");
  json doc = json::parse(std::ifstream(path));
  // Zero the fallback (buffer 0) so that only decoded data can give the right mesh.
  std::vector<unsigned char> zeros(g.bin.size(), 0);
  doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(zeros);
  doc["buffers"].push_back({{"byteLength", packed.size()},
                            {"uri", "data:application/octet-stream;base64," + base64(packed)}});
  write_file(path, doc.dump());
  expect_same_triangles(load(path), plain, 0.0f);
}

TEST_F(GltfFeatures, WebpTextureIsPreferredToItsFallback) {
  Gltf g = emissive_quad();
  g.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] =
      g.vec2s({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  const unsigned char red[4] = {255, 0, 0, 255};
  std::uint8_t* encoded = nullptr;
  const std::size_t size = WebPEncodeLosslessRGBA(red, 1, 1, 4, &encoded);
  ASSERT_GT(size, 0u);
  const int webp =
      g.push("images", {{"bufferView", g.view(encoded, size)}, {"mimeType", "image/webp"}});
  WebPFree(encoded);
  const int fallback = g.image_png(png(1, 1, 3, 8, {0, 0, 255}));
  g.push("textures",
         {{"source", fallback}, {"extensions", {{"EXT_texture_webp", {{"source", webp}}}}}});
  g.doc["extensionsUsed"] = {"EXT_texture_webp"};
  g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
  const Scene s = load(g.write_gltf(dir / "webp.gltf"));
  ASSERT_EQ(s.textures.size(), 1u);
  expect_near(s.textures[0].texels[0], {1, 0, 0, 1});
}

TEST_F(GltfFeatures, OrthographicCameraAndChosenScene) {
  Gltf g = emissive_quad();
  g.push("cameras",
         {{"type", "orthographic"},
          {"orthographic", {{"xmag", 2.0}, {"ymag", 1.0}, {"znear", 0.0}, {"zfar", 10.0}}}});
  g.push("nodes", {{"camera", 0}, {"translation", {0, 0, 5}}});
  g.doc["scenes"] = {{{"name", "first"}, {"nodes", {0}}}, {{"name", "second"}, {"nodes", {0, 1}}}};
  const fs::path path = g.write_gltf(dir / "ortho.gltf");
  const Scene s = load(path, "second");
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_TRUE(s.cameras[0].orthographic);
  EXPECT_FLOAT_EQ(s.cameras[0].xmag, 2.0f);
  EXPECT_FLOAT_EQ(s.cameras[0].ymag, 1.0f);
  EXPECT_EQ(load(path, "1").cameras.size(), 1u);
  EXPECT_EQ(load(path).cameras[0].name, "default"); // scene 0 has no camera
  EXPECT_THROW(load(path, "third"), irad::Error);
}

TEST_F(GltfFeatures, ExtensionsWarnUnlessRequired) {
  Gltf g = emissive_quad();
  g.doc["extensionsUsed"] = {"KHR_materials_clearcoat"};
  g.doc["materials"][0]["extensions"] = {{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}}}};
  load(g.write_gltf(dir / "used.gltf"));
  EXPECT_TRUE(warned("extension 'KHR_materials_clearcoat' is not supported"));
  g.doc["extensionsRequired"] = {"KHR_materials_clearcoat"};
  try {
    load(g.write_gltf(dir / "required.gltf"));
    FAIL() << "no error";
  } catch (const irad::Error& e) {
    EXPECT_NE(std::string(e.what()).find("extensionsRequired: the file requires extension "
                                         "'KHR_materials_clearcoat'"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(GltfFeatures, DataOutsideTheDeclaredBoundsIsRepairedWithAWarning) {
  Gltf g = emissive_quad();
  g.doc["accessors"][0]["max"][0] = 0.5; // POSITION's x reaches 1
  const Scene s = load(g.write_gltf(dir / "bounds.gltf"));
  EXPECT_FLOAT_EQ(s.bounds.hi.x, 1.0f);
  EXPECT_TRUE(warned("accessors[0].max[0]: "));
  EXPECT_TRUE(warned("irad computes the bounds itself"));
}

TEST_F(GltfFeatures, ProblemsInUnusedPartsAreOneWarningAndUsedOnesAnError) {
  Gltf g = emissive_quad();
  // Two broken accessors nobody uses, and a camera no node places.
  g.push("accessors", {{"componentType", kFloat}, {"count", 0}, {"type", "VEC3"}});
  g.push("accessors", {{"componentType", kFloat}, {"count", 3}, {"type", "VEC5"}});
  const Scene s = load(g.write_gltf(dir / "unused.gltf"));
  EXPECT_EQ(s.triangle_count(), 2u);
  const auto count = std::count_if(warnings.begin(), warnings.end(), [](const std::string& w) {
    return w.find("in parts irad does not use") != std::string::npos;
  });
  EXPECT_EQ(count, 1);
  // The same kind of problem in the POSITION accessor is the error of the file.
  g.doc["accessors"][0]["type"] = "VEC5";
  try {
    load(g.write_gltf(dir / "used.gltf"));
    FAIL() << "no error";
  } catch (const irad::Error& e) {
    EXPECT_NE(std::string(e.what()).find("used.gltf: accessors[0]"), std::string::npos) << e.what();
  }
}

// The quad with a clearcoat normal map (KHR_materials_clearcoat, which irad ignores) and neither
// TANGENT nor a normal map: the validator's MESH_PRIMITIVE_NO_TANGENT_SPACE at the primitive's
// material, a problem that the ignored extension alone raises.
Gltf clearcoat_normals_quad() {
  Gltf g = emissive_quad();
  g.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] =
      g.vec2s({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  g.push("textures", {{"source", g.image_png(png(1, 1, 3, 8, {128, 128, 255}))}});
  g.doc["materials"][0]["extensions"]["KHR_materials_clearcoat"] = {
      {"clearcoatFactor", 1.0}, {"clearcoatNormalTexture", {{"index", 0}}}};
  g.doc["extensionsUsed"] = {"KHR_materials_clearcoat"};
  return g;
}

TEST_F(GltfFeatures, ProblemsOfAnIgnoredExtensionAreWarningsAndOfAReadOneAnError) {
  Gltf g = clearcoat_normals_quad();
  const fs::path coat = g.write_gltf(dir / "coat.gltf");
  EXPECT_EQ(load(coat).triangle_count(), 2u);
  // One line naming the file and the element.
  const std::string tangents = "warning: " + coat.string() +
                               ": meshes[0].primitives[0].material: the material needs tangents "
                               "and neither the primitive nor a normal map gives them; irad "
                               "ignores extension 'KHR_materials_clearcoat'";
  EXPECT_EQ(std::count(warnings.begin(), warnings.end(), tangents), 1)
      << ::testing::PrintToString(warnings);
  // A problem inside the ignored extension's object is a warning too.
  g.doc["materials"][0]["extensions"]["KHR_materials_clearcoat"]["clearcoatFactor"] = 2.0;
  EXPECT_EQ(load(g.write_gltf(dir / "factor.gltf")).triangle_count(), 2u);
  EXPECT_TRUE(warned("factor.gltf: materials[0].extensions.KHR_materials_clearcoat.clearcoatFactor"
                     ": value 2.0 is out of range; irad ignores extension "
                     "'KHR_materials_clearcoat'"));
  // The same kind of problem in an extension irad reads, on the same material, is the error of
  // the file.
  g.doc["materials"][0]["extensions"]["KHR_materials_emissive_strength"] = {
      {"emissiveStrength", -2.0}};
  g.doc["extensionsUsed"].push_back("KHR_materials_emissive_strength");
  try {
    load(g.write_gltf(dir / "strength.gltf"));
    FAIL() << "no error";
  } catch (const irad::Error& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "strength.gltf: materials[0].extensions.KHR_materials_emissive_strength."
                  "emissiveStrength: value -2.0 is out of range"),
              std::string::npos)
        << e.what();
  }
}

} // namespace
