// The glTF material inputs beyond the base colour, read from small files and checked at a point
// of a triangle through brdf_inputs_at and mapped_normal (core/material/surface_material.h;
// docs/materials.md "The inputs"): metallicRoughnessTexture (linear; B metallic, G roughness),
// KHR_materials_ior, KHR_materials_specular (factor, colour, their textures), Lambertian by
// declaration, glTF's default material, normalTexture with its scale, and the two-uv-sets rule.
#include "core/material/surface_material.h"
#include "core/scene/scene.h"
#include "core/scene/texture.h"
#include "tests/gltf_loader_fixture.h"
#include "tests/gltf_test_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace IRAD_UNITY_ID {

using namespace gltf_test;
using glm::vec2;
using glm::vec3;
using irad::BrdfInputs;

// The quad's uv map: uv = (y, x). Its generated tangent is dp/du = +y with w = +1 (the map's
// determinant is -1: Tangents.FlatGridTangentIsDpDuAndSignFollowsTheUvWinding), so the
// bitangent w (N x T) is -x.
const std::vector<vec2> kUvs{{0, 0}, {0, 1}, {1, 1}, {1, 0}};

// Triangle 0 (kQuad's corners 0, 1, 2) at barycentrics (0, 1/2): the quad's centre, where
// uv = (1/2, 1/2) is the centre of a 1x1 texture's texel. The bilinear weights there are exactly
// 1 and 0, so a lookup returns the texel bit for bit.
constexpr vec2 kCentre{0.0f, 0.5f};

// f0 of the dielectric at glTF's default ior 1.5, ((ior - 1)/(ior + 1))^2, in float as the code
// computes it: 0.0400000028, one float step above 0.04f.
const float kF0 = [] {
  const float r = (1.5f - 1.0f) / (1.5f + 1.0f);
  return r * r;
}();

// An 8-bit value v of a linear texture: v / 255 in float, as the decoder computes it.
float unorm8(int v) {
  return float(v) / 255.0f;
}

// A data: URI of a PNG.
std::string png_uri(const std::vector<unsigned char>& bytes) {
  return "data:image/png;base64," + base64(bytes);
}

class MaterialInputs : public GltfLoader {
protected:
  // The unit quad (kQuad, normals +z, TEXCOORD_0 = kUvs and TEXCOORD_1, TEXCOORD_2 the same) on
  // one node, drawn with `material` as materials[0] (or glTF's default material when `material`
  // is null); textures[i] shows images[i], the PNG pngs[i]. The material's extensions are listed
  // in extensionsUsed.
  Scene load_quad(const json& material, const std::vector<std::vector<unsigned char>>& pngs,
                  const std::string& name) {
    Gltf g;
    for (const std::vector<unsigned char>& bytes : pngs)
      g.push("textures", {{"source", g.push("images", {{"uri", png_uri(bytes)}})}});
    if (!material.is_null()) g.push("materials", material);
    json p = quad_primitive(g, material.is_null() ? -1 : 0, kUpNormals);
    const int uv = g.vec2s(kUvs);
    for (const char* set : {"TEXCOORD_0", "TEXCOORD_1", "TEXCOORD_2"}) p["attributes"][set] = uv;
    g.push("meshes", {{"primitives", {p}}});
    g.push("nodes", {{"mesh", 0}});
    g.doc["scenes"] = {{{"nodes", {0}}}};
    g.doc["scene"] = 0;
    if (material.contains("extensions"))
      for (const auto& [extension, value] : material.at("extensions").items())
        g.doc["extensionsUsed"].push_back(extension);
    return load(g.write_gltf(dir / (name + ".gltf")));
  }

  // brdf_inputs_at at kCentre, after checking that the point's uv is (1/2, 1/2) there.
  static BrdfInputs at_centre(const Scene& s) {
    EXPECT_EQ(s.triangle_count(), 2u);
    if (!s.uvs.empty()) {
      const glm::uvec3& tri = s.triangles[0];
      const vec2 uv = 0.5f * s.uvs[tri.x] + 0.5f * s.uvs[tri.z];
      EXPECT_EQ(uv.x, 0.5f);
      EXPECT_EQ(uv.y, 0.5f);
    }
    return irad::brdf_inputs_at(s, 0, kCentre);
  }
};

// metallicRoughnessTexture texel (200, 128, 64): roughness = roughnessFactor x G / 255 and
// metallic = metallicFactor x B / 255, the texel read linearly (sRGB decoding would turn 128 into
// 0.2159); R (occlusion) is not read. Exact: the lookup returns the texel and both sides compute
// one float product.
TEST_F(MaterialInputs, MetallicRoughnessTextureScalesTheFactorsLinearly) {
  const json material = {{"pbrMetallicRoughness",
                          {{"metallicFactor", 0.5},
                           {"roughnessFactor", 0.75},
                           {"metallicRoughnessTexture", {{"index", 0}}}}}};
  const Scene s = load_quad(material, {png(1, 1, 3, 8, {200, 128, 64})}, "mr");
  ASSERT_GE(s.material_of(0).metallic_roughness_texture, 0);
  const BrdfInputs in = at_centre(s);
  EXPECT_EQ(in.roughness, 0.75f * unorm8(128));
  EXPECT_EQ(in.metallic, 0.5f * unorm8(64));
  EXPECT_NEAR(in.roughness, 0.75 * 128.0 / 255.0, 1e-7); // float rounding: measured 3.7e-8
  EXPECT_NEAR(in.metallic, 0.5 * 64.0 / 255.0, 1e-7);    // measured 7.4e-9
  // The texture leaves the dielectric's Fresnel alone: ior 1.5, specular 1.
  EXPECT_EQ(in.f0, vec3(kF0));
  EXPECT_EQ(in.f90, 1.0f);
}

// f0 = ((ior - 1)/(ior + 1))^2 with specular 1: 0.04 at 1.5 (0.0400000028 in float, 1 float step
// above 0.04f), 1/9 at 2 (0.111111119, 1 float step above 1.0f/9), exactly 1 at ior 0.
TEST_F(MaterialInputs, IorSetsF0) {
  const auto f0_at = [this](double ior, const std::string& name) {
    const json material = {{"extensions", {{"KHR_materials_ior", {{"ior", ior}}}}}};
    const Scene s = load_quad(material, {}, name);
    EXPECT_EQ(s.material_of(0).ior, float(ior));
    const BrdfInputs in = at_centre(s);
    EXPECT_EQ(in.f90, 1.0f);
    EXPECT_EQ(in.f0.x, in.f0.y);
    EXPECT_EQ(in.f0.x, in.f0.z);
    return in.f0.x;
  };
  const float f0_15 = f0_at(1.5, "ior15");
  EXPECT_EQ(f0_15, kF0);
  EXPECT_FLOAT_EQ(f0_15, 0.04f);
  EXPECT_FLOAT_EQ(f0_at(2.0, "ior2"), 1.0f / 9.0f);
  EXPECT_EQ(f0_at(0.0, "ior0"), 1.0f);
}

// ior in (0, 1) is refused with one line naming the file and
// materials[i].extensions.KHR_materials_ior; here materials[1] (materials[0] is unused).
TEST_F(MaterialInputs, IorBetweenZeroAndOneIsRefused) {
  Gltf g;
  g.push("materials", json::object());
  g.push("materials", {{"extensions", {{"KHR_materials_ior", {{"ior", 0.5}}}}}});
  g.doc["extensionsUsed"] = {"KHR_materials_ior"};
  g.push("meshes", {{"primitives", {quad_primitive(g, 1, kUpNormals)}}});
  g.push("nodes", {{"mesh", 0}});
  g.doc["scenes"] = {{{"nodes", {0}}}};
  g.doc["scene"] = 0;
  expect_error(g.write_gltf(dir / "ior05.gltf"), "materials[1].extensions.KHR_materials_ior",
               "ior must be 0 or at least 1");
}

// specularFactor s and specularColorFactor c: f0 = min(f0 c, 1) s per channel and f90 = s.
// With s = 0.5 and c = (2, 30, 0.5): (0.08 x 0.5, min(1.2, 1) x 0.5, 0.02 x 0.5). Exact: every
// product but the clamped one is by a power of two.
TEST_F(MaterialInputs, SpecularFactorAndColourScaleF0AndClampIt) {
  const json material = {
      {"extensions",
       {{"KHR_materials_specular",
         {{"specularFactor", 0.5}, {"specularColorFactor", {2.0, 30.0, 0.5}}}}}}};
  const Scene s = load_quad(material, {}, "specular");
  const BrdfInputs in = at_centre(s);
  EXPECT_EQ(in.f90, 0.5f);
  EXPECT_EQ(in.f0, vec3(kF0, 0.5f, kF0 * 0.25f));
  EXPECT_FLOAT_EQ(in.f0.x, 0.04f);
  EXPECT_FLOAT_EQ(in.f0.z, 0.01f);
  EXPECT_EQ(in.metallic, 1.0f); // glTF's default metallicFactor
}

// specularTexture's alpha scales specularFactor, linearly (alpha is never sRGB-decoded); its rgb
// (0, 0, 0 here) is not read: s = 0.5 x 64/255, f0 = f0(1.5) s, f90 = s. Exact: the same float
// products on both sides.
TEST_F(MaterialInputs, SpecularTextureAlphaScalesTheFactor) {
  const json material = {{"extensions",
                          {{"KHR_materials_specular",
                            {{"specularFactor", 0.5}, {"specularTexture", {{"index", 0}}}}}}}};
  const Scene s = load_quad(material, {png(1, 1, 4, 8, {0, 0, 0, 64})}, "spectex");
  ASSERT_GE(s.material_of(0).specular_texture, 0);
  const BrdfInputs in = at_centre(s);
  const float spec = 0.5f * unorm8(64);
  EXPECT_EQ(in.f90, spec);
  EXPECT_EQ(in.f0, vec3(kF0 * spec));
  EXPECT_NEAR(in.f90, 32.0 / 255.0, 1e-7); // float rounding: measured 7.4e-9
}

// specularColorTexture's rgb scales the colour after sRGB decoding: 188 is 0.502886 linear (not
// 188/255 = 0.737), 255 is 1, 0 is 0. The first check is exact against the decoder's own
// srgb_to_linear (core/scene/texture.h); the second against the sRGB EOTF in double,
// ((188/255 + 0.055)/1.055)^2.4 = 0.50288646, within float rounding (measured 1.6e-8).
TEST_F(MaterialInputs, SpecularColorTextureIsDecodedFromSrgb) {
  const json material = {
      {"extensions", {{"KHR_materials_specular", {{"specularColorTexture", {{"index", 0}}}}}}}};
  const Scene s = load_quad(material, {png(1, 1, 3, 8, {188, 255, 0})}, "speccolour");
  ASSERT_GE(s.material_of(0).specular_color_texture, 0);
  const BrdfInputs in = at_centre(s);
  EXPECT_EQ(in.f0, vec3(kF0 * irad::srgb_to_linear(unorm8(188)), kF0, 0.0f));
  EXPECT_NEAR(in.f0.x / kF0, 0.50288646, 1e-6);
  EXPECT_EQ(in.f90, 1.0f);
}

// metallicFactor 0 with specularFactor 0 declares a Lambertian surface: no texture changes the
// inputs (here a metallicRoughnessTexture of B = 255 and a specular colour), m = f0 = f90 = 0.
TEST_F(MaterialInputs, MetallicAndSpecularZeroIsLambertian) {
  const json material = {{"pbrMetallicRoughness",
                          {{"baseColorFactor", {0.25, 0.5, 0.75, 1.0}},
                           {"metallicFactor", 0.0},
                           {"metallicRoughnessTexture", {{"index", 0}}}}},
                         {"extensions",
                          {{"KHR_materials_specular",
                            {{"specularFactor", 0.0}, {"specularColorFactor", {1, 1, 1}}}}}}};
  const Scene s = load_quad(material, {png(1, 1, 3, 8, {255, 255, 255})}, "lambert");
  EXPECT_TRUE(s.material_of(0).lambertian());
  const BrdfInputs in = at_centre(s);
  EXPECT_EQ(in.metallic, 0.0f);
  EXPECT_EQ(in.f0, vec3(0.0f));
  EXPECT_EQ(in.f90, 0.0f);
  EXPECT_TRUE(in.lambertian());
  EXPECT_EQ(in.base, vec3(0.25f, 0.5f, 0.75f));
}

// A primitive without material gets glTF's default: white, metallic 1, roughness 1, ior 1.5,
// specular 1: a rough white metal, not Lambertian.
TEST_F(MaterialInputs, PrimitiveWithoutMaterialGetsTheGltfDefault) {
  const Scene s = load_quad(json(), {}, "default");
  const irad::Material& m = s.material_of(0);
  EXPECT_FALSE(m.lambertian());
  EXPECT_FALSE(m.specular); // not a mirror: roughness 1
  const BrdfInputs in = at_centre(s);
  EXPECT_EQ(in.metallic, 1.0f);
  EXPECT_EQ(in.roughness, 1.0f);
  EXPECT_EQ(in.base, vec3(1.0f));
  EXPECT_EQ(in.f0, vec3(kF0));
  EXPECT_EQ(in.f90, 1.0f);
  EXPECT_FALSE(in.lambertian());
}

// normalTexture on the quad (N = +z, generated T = +y, B = -x). A texel t gives
// n = 2 t - 1 (read linearly) with x, y times `scale`, and the normal normalize(n.x T + n.y B +
// n.z N). 128 is 0.5 + 1/510, so e = 2 x 128/255 - 1 = 1/255 remains in x or y.
TEST_F(MaterialInputs, NormalMapTurnsTheNormalInTheTangentFrame) {
  const vec3 up(0, 0, 1);
  const float e = 1.0f / 255.0f;
  const auto normal_at = [&](const std::vector<std::uint16_t>& texel, double scale,
                             const std::string& name) {
    const json material = {{"normalTexture", {{"index", 0}, {"scale", scale}}}};
    const Scene s = load_quad(material, {png(1, 1, 3, 8, texel)}, name);
    EXPECT_GE(s.material_of(0).normal_texture, 0);
    EXPECT_EQ(s.tangents.size(), s.positions.size());
    // Exact: an axis-aligned uv map on an axis-aligned quad (as in TangentLoader).
    for (std::uint32_t v : {s.triangles[0].x, s.triangles[0].y, s.triangles[0].z})
      EXPECT_EQ(s.tangents[v], glm::vec4(0, 1, 0, 1));
    return irad::mapped_normal(s, 0, kCentre, up);
  };
  // (255, 128, 128): tangent-space +x, the tangent (+u in the world: +y), tilted by the 8-bit
  // quantisation toward B and N: normalize(-e, 1, e), 5.5e-3 rad from T. 1e-6 for float
  // rounding: measured 5.9e-8 per component against the direction in double.
  const vec3 along_u = normal_at({255, 128, 128}, 1.0, "tangent");
  expect_near(along_u, glm::normalize(vec3(-e, 1.0f, e)), 1e-6f);
  EXPECT_NEAR(glm::length(along_u), 1.0f, 1e-6f); // measured 0
  EXPECT_GT(glm::dot(along_u, vec3(0, 1, 0)), std::cos(5.6e-3f));
  // scale 0 zeroes x and y: n = e N, normalised to N exactly (IEEE sqrt(e^2) = e, e / e = 1).
  EXPECT_EQ(normal_at({255, 128, 128}, 0.0, "flat_scale"), up);
  // (128, 128, 255) is the flat texel up to the quantisation: normalize(-e, e, 1), 5.5e-3 rad
  // from N (measured 5.9e-8 per component, as above).
  const vec3 flat = normal_at({128, 128, 255}, 1.0, "flat_texel");
  expect_near(flat, glm::normalize(vec3(-e, e, 1.0f)), 1e-6f);
  EXPECT_GT(glm::dot(flat, up), std::cos(5.6e-3f));
}

// A material's textures fill two uv slots in the order base colour, emissive, metallicRoughness,
// specular, specular colour, normal: base colour on TEXCOORD_1 takes slot 0, emissive on
// TEXCOORD_2 slot 1, and the normal map on TEXCOORD_0 is dropped with one warning line; the
// normal stays the interpolated one and the scene has no tangents.
TEST_F(MaterialInputs, AThirdTexcoordSetIsDroppedWithAWarning) {
  const json material = {
      {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"texCoord", 1}}}}},
      {"emissiveFactor", {1.0, 1.0, 1.0}},
      {"emissiveTexture", {{"index", 0}, {"texCoord", 2}}},
      {"normalTexture", {{"index", 1}, {"texCoord", 0}}}};
  const Scene s = load_quad(
      material, {png(1, 1, 3, 8, {255, 255, 255}), png(1, 1, 3, 8, {255, 128, 128})}, "third");
  const irad::Material& m = s.material_of(0);
  EXPECT_EQ(m.base_color_map.texcoord, 0);
  EXPECT_EQ(m.emissive_map.texcoord, 1);
  EXPECT_EQ(m.normal_texture, -1);
  EXPECT_TRUE(s.tangents.empty());
  const vec3 up(0, 0, 1);
  EXPECT_EQ(irad::mapped_normal(s, 0, kCentre, up), up);
  const std::string line = "warning: " + (dir / "third.gltf").string() +
                           ": materials[0].normalTexture: a third TEXCOORD set in one material; "
                           "ignored";
  EXPECT_EQ(std::count(warnings.begin(), warnings.end(), line), 1)
      << ::testing::PrintToString(warnings);
}

} // namespace
