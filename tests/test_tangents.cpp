// MikkTSpace tangent frames (core/mesh/tangents.h) and the glTF reader's tangents: planar meshes
// with known uv axes (tangent = dp/du, w from the uv winding), mirrored uvs (w = -1 and a vertex
// split at the seam), the reference implementation's output on a curved, mirrored grid,
// degenerate triangles, and TANGENT read, generated, placed, compacted and animated by the loader.
#include "core/animation/animation.h"
#include "core/mesh/tangents.h"
#include "core/scene/scene.h"
#include "tests/gltf_loader_fixture.h"
#include "tests/gltf_test_scene.h"

#include <array>
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>
#include <stdexcept>
#include <vector>

namespace IRAD_UNITY_ID {

using glm::vec2;
using glm::vec3;
using glm::vec4;

// Angle between two directions, in radians (atan2 of |a x b| and a . b: exact near 0).
double angle(const vec3& a, const vec3& b) {
  const glm::dvec3 x(a), y(b);
  return std::atan2(glm::length(glm::cross(x, y)), glm::dot(x, y));
}

struct Mesh {
  std::vector<vec3> positions, normals;
  std::vector<vec2> uvs;
  std::vector<glm::uvec3> triangles;
};

// An n x n grid over the unit square in z = 0 facing +z, uv = map(x, y).
template <class Map>
Mesh flat_grid(int n, Map map) {
  Mesh m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const vec3 p(float(i) / float(n), float(j) / float(n), 0.0f);
      m.positions.push_back(p);
      m.normals.emplace_back(0.0f, 0.0f, 1.0f);
      m.uvs.push_back(map(p.x, p.y));
    }
  const auto at = [n](int i, int j) { return std::uint32_t(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return m;
}

std::vector<vec4> tangents_of(const Mesh& m) {
  return irad::mikktspace_tangents(m.positions, m.normals, m.uvs, m.triangles);
}

// Affine uv maps uv = M (x, y) + c of the flat grid: every corner's tangent is dp/du, the first
// column of M^-1, and w = +1 exactly where w cross(n, dp/du) points toward -dp/dv (up the image,
// glTF's bitangent), i.e. where det M < 0 (v grows down the image while y grows up).
TEST(Tangents, FlatGridTangentIsDpDuAndSignFollowsTheUvWinding) {
  const std::vector<glm::mat2> maps{
      {1.0f, 0.0f, 0.0f, -1.0f},  // u = x, v = -y: the usual glTF image on the quad
      {0.0f, 1.0f, 1.0f, 0.0f},   // u = y, v = x: image turned 90 degrees
      {1.0f, 0.0f, 0.0f, 1.0f},   // u = x, v = y: mirrored (v up the quad)
      {2.0f, 0.5f, -0.3f, -1.5f}, // sheared and scaled, det < 0
      {-0.7f, 0.4f, 1.1f, 0.9f},  // sheared, det < 0
      {0.8f, 0.6f, -0.6f, 0.8f},  // a rotation, det > 0: mirrored
  };
  double worst = 0.0;
  for (const glm::mat2& map : maps) {
    const Mesh m = flat_grid(3, [&](float x, float y) { return map * vec2(x, y) + 0.25f; });
    const glm::mat2 inverse = glm::inverse(map);
    const vec3 dp_du(inverse[0], 0.0f), dp_dv(inverse[1], 0.0f);
    const float w = glm::determinant(map) < 0.0f ? 1.0f : -1.0f;
    EXPECT_GT(w * glm::dot(glm::cross(vec3(0, 0, 1), dp_du), -dp_dv), 0.0f);
    for (const vec4& t : tangents_of(m)) {
      worst = std::max(worst, angle(vec3(t), dp_du));
      EXPECT_EQ(t.w, w);
      EXPECT_NEAR(glm::length(vec3(t)), 1.0f, 1e-6f);
    }
  }
  EXPECT_LT(worst, 1e-6); // measured 2.2e-7 rad (float rounding)
  const std::vector<vec4> usual =
      tangents_of(flat_grid(1, [](float x, float y) { return vec2(x, 1.0f - y); }));
  for (const vec4& t : usual) EXPECT_EQ(t, vec4(1, 0, 0, 1));
}

// u mirrored at x = 1/2 (u = |x - 1/2|): the right half has tangent +x and w = +1, the left
// half -x and w = -1 (its bitangent w cross(n, -x) = +y still points up the image). The seam
// vertices weld (same position, normal and uv) but get one frame per side: split_by_tangent
// copies each of them once.
TEST(Tangents, MirroredUvsGiveMinusOneAndSplitTheSeam) {
  const int n = 4;
  const Mesh m = flat_grid(n, [](float x, float y) { return vec2(std::fabs(x - 0.5f), 1 - y); });
  const std::vector<vec4> t = tangents_of(m);
  for (std::size_t k = 0; k < t.size(); ++k) {
    const glm::uvec3& tri = m.triangles[k / 3];
    const float cx = (m.positions[tri.x].x + m.positions[tri.y].x + m.positions[tri.z].x) / 3;
    const vec4 expected = cx > 0.5f ? vec4(1, 0, 0, 1) : vec4(-1, 0, 0, -1);
    EXPECT_EQ(t[k], expected) << "corner " << k;
  }
  const irad::TangentVertices split = irad::split_by_tangent(m.positions.size(), m.triangles, t);
  EXPECT_EQ(split.source.size(), m.positions.size() + n + 1); // one copy per seam vertex
  for (std::size_t v = 0; v < m.positions.size(); ++v) EXPECT_EQ(split.source[v], v);
  for (std::size_t v = m.positions.size(); v < split.source.size(); ++v)
    EXPECT_FLOAT_EQ(m.positions[split.source[v]].x, 0.5f);
  for (std::size_t k = 0; k < t.size(); ++k) {
    const std::uint32_t v = split.triangles[k / 3][int(k % 3)];
    EXPECT_EQ(split.tangents[v], t[k]);
    EXPECT_EQ(split.source[v], m.triangles[k / 3][int(k % 3)]);
  }
}

// A curved 4 x 2 grid with smooth (not face) normals and u mirrored at x = 1/2, and the corner
// tangents the reference mikktspace.c (github.com/mmikk/MikkTSpace, genTangSpaceDefault) gives
// for it with uv (u, 1 - v), Blender's convention, as glTF exporters run it.
Mesh bumpy_mirrored_grid() {
  Mesh m;
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= 2; ++j) {
      const float x = 0.25f * float(i), y = 0.5f * float(j);
      m.positions.emplace_back(x, y, 0.2f * std::sin(3.0f * x + 1.0f) * std::cos(2.0f * y));
      m.normals.emplace_back(-0.6f * std::cos(3.0f * x + 1.0f) * std::cos(2.0f * y) + 0.05f * y,
                             0.4f * std::sin(3.0f * x + 1.0f) * std::sin(2.0f * y), 1.0f);
      m.uvs.emplace_back(1.5f * std::fabs(x - 0.5f), 1.0f - y + 0.1f * x * x);
    }
  for (unsigned i = 0; i < 4; ++i)
    for (unsigned j = 0; j < 2; ++j) {
      const unsigned a = 3 * i + j, b = a + 3, c = b + 1, d = a + 1;
      m.triangles.emplace_back(a, b, c);
      m.triangles.emplace_back(a, c, d);
    }
  return m;
}

const std::array<vec4, 48> kReference{{
    {-0.9509536f, -0.025490636f, -0.30828145f, -1},
    {-0.99313653f, -0.048975103f, 0.10621363f, -1},
    {-0.99519354f, -0.031356733f, 0.092771448f, -1},
    {-0.9509536f, -0.025490636f, -0.30828145f, -1},
    {-0.99519354f, -0.031356733f, 0.092771448f, -1},
    {-0.98963773f, -0.05169341f, -0.13395888f, -1},
    {-0.98963773f, -0.05169341f, -0.13395888f, -1},
    {-0.99519354f, -0.031356733f, 0.092771448f, -1},
    {-0.99939579f, -0.030619623f, 0.016449351f, -1},
    {-0.98963773f, -0.05169341f, -0.13395888f, -1},
    {-0.99939579f, -0.030619623f, 0.016449351f, -1},
    {-0.98392183f, 0.012273738f, 0.17817758f, -1},
    {-0.99313653f, -0.048975103f, 0.10621363f, -1},
    {-0.89894032f, -0.072033741f, 0.43210819f, -1},
    {-0.95720357f, -0.056337193f, 0.28387949f, -1},
    {-0.99313653f, -0.048975103f, 0.10621363f, -1},
    {-0.95720357f, -0.056337193f, 0.28387949f, -1},
    {-0.99519354f, -0.031356733f, 0.092771448f, -1},
    {-0.99519354f, -0.031356733f, 0.092771448f, -1},
    {-0.95720357f, -0.056337193f, 0.28387949f, -1},
    {-0.98706639f, -0.098191291f, -0.12672165f, -1},
    {-0.99519354f, -0.031356733f, 0.092771448f, -1},
    {-0.98706639f, -0.098191291f, -0.12672165f, -1},
    {-0.99939579f, -0.030619623f, 0.016449351f, -1},
    {0.89562702f, 0.11184196f, -0.43051547f, 1},
    {0.85101122f, 0.1345831f, -0.50760931f, 1},
    {0.93606234f, 0.14684027f, -0.31972668f, 1},
    {0.89562702f, 0.11184196f, -0.43051547f, 1},
    {0.93606234f, 0.14684027f, -0.31972668f, 1},
    {0.95028174f, 0.10755658f, -0.29222634f, 1},
    {0.95028174f, 0.10755658f, -0.29222634f, 1},
    {0.93606234f, 0.14684027f, -0.31972668f, 1},
    {0.96952236f, 0.1444826f, 0.19786677f, 1},
    {0.95028174f, 0.10755658f, -0.29222634f, 1},
    {0.96952236f, 0.1444826f, 0.19786677f, 1},
    {0.98654419f, 0.10525771f, 0.12510513f, 1},
    {0.85101122f, 0.1345831f, -0.50760931f, 1},
    {0.91963571f, 0.15552597f, -0.36066839f, 1},
    {0.97038192f, 0.14554887f, -0.1928068f, 1},
    {0.85101122f, 0.1345831f, -0.50760931f, 1},
    {0.97038192f, 0.14554887f, -0.1928068f, 1},
    {0.93606234f, 0.14684027f, -0.31972668f, 1},
    {0.93606234f, 0.14684027f, -0.31972668f, 1},
    {0.97038192f, 0.14554887f, -0.1928068f, 1},
    {0.9764201f, 0.15272251f, 0.15257655f, 1},
    {0.93606234f, 0.14684027f, -0.31972668f, 1},
    {0.9764201f, 0.15272251f, 0.15257655f, 1},
    {0.96952236f, 0.1444826f, 0.19786677f, 1},
}};

TEST(Tangents, MatchTheReferenceImplementation) {
  const Mesh m = bumpy_mirrored_grid();
  const std::vector<vec4> t = tangents_of(m);
  ASSERT_EQ(t.size(), kReference.size());
  double worst = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    worst = std::max(worst, angle(vec3(t[k]), vec3(kReference[k])));
    EXPECT_EQ(t[k].w, kReference[k].w) << "corner " << k;
  }
  EXPECT_LT(worst, 1e-5); // measured 1.6e-7 rad: float rounding (the reference sees 1 - v)
  // The three seam vertices (x = 1/2) get two frames each.
  EXPECT_EQ(irad::split_by_tangent(m.positions.size(), m.triangles, t).source.size(), 18u);
}

// A quad whose second triangle has no uv area (its corners 0 and 3 share a uv): it joins the
// group of the first triangle at the corners the two share and takes their frames there; its
// own corner 3 no group reaches gets a unit tangent orthogonal to the normal and w = 1.
TEST(Tangents, ZeroUvAreaTrianglesTakeTheirNeighboursFrames) {
  const Mesh m{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}},
               std::vector<vec3>(4, vec3(0.2f, 0, 1)),
               {{0, 1}, {1, 1}, {1, 0}, {0, 1}},
               {{0, 1, 2}, {0, 2, 3}}};
  const std::vector<vec4> t = tangents_of(m);
  const vec3 n = glm::normalize(m.normals[0]);
  EXPECT_EQ(t[3], t[0]); // vertex 0
  EXPECT_EQ(t[4], t[2]); // vertex 2
  EXPECT_EQ(t[0].w, 1.0f);
  // dp/du = +x made orthogonal to n: measured 2.9e-9 rad off; t[5] . n measured 3.0e-8.
  const vec3 expected = glm::normalize(vec3(1, 0, 0) - 0.2f / 1.04f * vec3(0.2f, 0, 1));
  EXPECT_NEAR(angle(vec3(t[0]), expected), 0.0, 1e-6);
  EXPECT_NEAR(glm::dot(vec3(t[5]), n), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(vec3(t[5])), 1.0f, 1e-6f);
  EXPECT_EQ(t[5].w, 1.0f);
  // A lone triangle without uv area: every corner gets a unit tangent orthogonal to its normal.
  const Mesh lone{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                  {{1, 0, 0}, {0, 0, 1}, {0, 0.6f, 0.8f}},
                  std::vector<vec2>(3, vec2(0.5f)),
                  {{0, 1, 2}}};
  const std::vector<vec4> l = tangents_of(lone);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(glm::dot(vec3(l[std::size_t(c)]), lone.normals[std::size_t(c)]), 0.0f, 1e-6f);
    EXPECT_NEAR(glm::length(vec3(l[std::size_t(c)])), 1.0f, 1e-6f);
    EXPECT_EQ(l[std::size_t(c)].w, 1.0f);
  }
}

// A triangle with two corners at one position takes, per corner, the frame of the first good
// corner of the same (welded) vertex.
TEST(Tangents, DegenerateTrianglesCopyTheFramesOfTheirVertices) {
  Mesh m = bumpy_mirrored_grid();
  const std::size_t good = m.triangles.size();
  m.triangles.emplace_back(4, 7, 7);
  const std::vector<vec4> t = tangents_of(m);
  ASSERT_EQ(t.size(), 3 * good + 3);
  for (int c = 0; c < 3; ++c) {
    const std::uint32_t v = m.triangles[good][c];
    std::size_t first = 0;
    while (m.triangles[first / 3][int(first % 3)] != v) ++first;
    EXPECT_EQ(t[3 * good + std::size_t(c)], t[first]) << "corner " << c;
  }
  EXPECT_NE(t[3 * good], t[3 * good + 1]); // vertices 4 and 7 have frames of their own
}

TEST(Tangents, SplitKeepsAgreeingVerticesAndChecksItsInput) {
  const std::vector<glm::uvec3> tris{{0, 1, 2}, {0, 2, 3}};
  const vec4 a(1, 0, 0, 1), b(0, 1, 0, -1);
  const irad::TangentVertices same = irad::split_by_tangent(5, tris, {a, a, a, a, a, a});
  EXPECT_EQ(same.source, (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(same.triangles, tris);
  EXPECT_EQ(same.tangents[4], vec4(0.0f)); // no triangle uses vertex 4
  const irad::TangentVertices split = irad::split_by_tangent(4, tris, {a, a, a, b, b, b});
  EXPECT_EQ(split.source, (std::vector<std::uint32_t>{0, 1, 2, 3, 0, 2}));
  EXPECT_EQ(split.triangles[1], glm::uvec3(4, 5, 3));
  EXPECT_EQ(split.tangents[3], b);
  EXPECT_THROW(irad::split_by_tangent(4, tris, {a}), std::invalid_argument);
  EXPECT_THROW(irad::split_by_tangent(3, tris, {a, a, a, a, a, a}), std::invalid_argument);
  EXPECT_THROW(irad::mikktspace_tangents({vec3(0)}, {}, {}, {}), std::invalid_argument);
}

// Without normals every corner becomes its own vertex with its triangle's normal.
TEST(Tangents, FlatShadingGivesEveryCornerAVertex) {
  const Mesh m{{{0, 0, 0}, {1, 0, 0}, {1, 1, 1}, {0, 1, 1}},
               {},
               {{0, 1}, {1, 1}, {1, 0}, {0, 0}},
               {{0, 1, 2}, {0, 2, 3}}};
  const irad::TangentVertices tv = irad::tangent_vertices(m.positions, {}, m.uvs, m.triangles);
  EXPECT_EQ(tv.source, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(tv.triangles[1], glm::uvec3(3, 4, 5));
  const vec3 n = glm::normalize(vec3(0, -1, 1)); // both triangles: (p1 - p0) x (p2 - p0)
  for (const vec4& t : tv.tangents) {
    EXPECT_NEAR(angle(vec3(t), vec3(1, 0, 0)), 0.0, 1e-6); // measured 0
    EXPECT_NEAR(glm::dot(vec3(t), n), 0.0f, 1e-6f);
    EXPECT_EQ(t.w, 1.0f);
  }
}

// A node whose 3x3 block mirrors x and a rest pose of a skin or morph: Animation::deform moves
// tangents by the matrix (w flips with det < 0) and adds the targets' displacements.
TEST(Tangents, DeformedPartsCarryTheirTangents) {
  irad::Animation anim;
  anim.nodes.emplace_back();
  irad::Animation::DeformedPart part;
  part.vertices = {0};
  part.positions = {vec3(0.0f)};
  part.normals = {vec3(0, 0, 1)};
  part.tangents = {vec4(1, 0, 0, 1)};
  part.position_targets = {{vec3(0.0f)}};
  part.tangent_targets = {{vec3(-1, 1, 0)}};
  const glm::dmat4 mirror = glm::scale(glm::dmat4(1.0), glm::dvec3(-2.0, 1.0, 1.0));
  std::vector<vec3> p, n;
  std::vector<vec4> t;
  anim.deform(part, {mirror}, {0.0}, p, n, &t);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0], vec4(-1, 0, 0, -1));
  anim.deform(part, {glm::dmat4(1.0)}, {1.0}, p, n, &t); // t = (1, 0, 0) + (-1, 1, 0)
  EXPECT_EQ(t[0], vec4(0, 1, 0, 1));
  anim.deform(part, {glm::dmat4(1.0)}, {0.0}, p, n); // no tangents asked for
}

// ---------------------------------------------------------------------------------------------
// The glTF reader.

using namespace gltf_test;

class TangentLoader : public GltfLoader {
protected:
  // The unit quad (kQuad, normals +z) with TEXCOORD_0 (x, 1 - y) (the image upright on it), a
  // material with a flat normal map when `normal_map`, the file's TANGENT when given, on a node.
  static Gltf quad(json node, bool normal_map, const std::vector<vec4>& tangents = {}) {
    Gltf g;
    g.image_png(png(1, 1, 3, 8, {128, 128, 255}));
    g.push("textures", {{"source", 0}});
    g.push("materials", normal_map ? json{{"normalTexture", {{"index", 0}}}} : json::object());
    json p = quad_primitive(g, 0, kUpNormals);
    p["attributes"]["TEXCOORD_0"] = g.vec2s({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    if (!tangents.empty())
      p["attributes"]["TANGENT"] = g.accessor(
          g.view(tangents.data(), tangents.size() * sizeof(vec4)), kFloat, tangents.size(), "VEC4");
    g.push("meshes", {{"primitives", {p}}});
    node["mesh"] = 0;
    g.push("nodes", node);
    g.doc["scenes"] = {{{"nodes", {0}}}};
    g.doc["scene"] = 0;
    return g;
  }
};

// Generated for a normal map without TANGENT: dp/du = +x with w = +1. The exact value: the
// quad's uv map is a scaled axis map, so float arithmetic gives (1, 0, 0) exactly.
TEST_F(TangentLoader, GeneratedWhereANormalMapHasNoTangent) {
  const Scene s = load(quad({}, true).write_gltf(dir / "generated.gltf"));
  ASSERT_EQ(s.tangents.size(), s.positions.size());
  for (const vec4& t : s.tangents) EXPECT_EQ(t, vec4(1, 0, 0, 1));
}

// A node mirroring x: t' = normalize(A t) = -x and w' = w sign(det A) = -1, so that the
// bitangent w' cross(n', t') is still +y, up the image as it lies in the world.
TEST_F(TangentLoader, AMirroringNodeFlipsTheSign) {
  const Scene s = load(quad({{"scale", {-1, 1, 1}}}, true).write_gltf(dir / "mirror.gltf"));
  ASSERT_EQ(s.tangents.size(), 4u);
  for (std::size_t v = 0; v < 4; ++v) {
    EXPECT_EQ(s.tangents[v], vec4(-1, 0, 0, -1));
    expect_near(s.tangents[v].w * glm::cross(s.normals[v], vec3(s.tangents[v])), {0, 1, 0});
  }
}

// The file's TANGENT is used (not regenerated), placed by the node: a rotation by 90 degrees
// about z takes (0, 1, 0) to (-1, 0, 0); w is kept.
TEST_F(TangentLoader, TheFilesTangentIsPlaced) {
  const float h = std::sqrt(0.5f);
  const Gltf g = quad({{"rotation", {0, 0, h, h}}}, true, std::vector<vec4>(4, vec4(0, 1, 0, -1)));
  const Scene s = load(g.write_gltf(dir / "file.gltf"));
  ASSERT_EQ(s.tangents.size(), 4u);
  for (const vec4& t : s.tangents) expect_near(t, vec4(-1, 0, 0, -1), 1e-6f); // float rotation
}

// Without a normal map the scene has no tangents, even where the file has TANGENT.
TEST_F(TangentLoader, NoNormalMapNoTangents) {
  const Gltf g = quad({}, false, std::vector<vec4>(4, vec4(0, 1, 0, 1)));
  EXPECT_TRUE(load(g.write_gltf(dir / "none.gltf")).tangents.empty());
}

// A second primitive without a normal map shares the scene's tangent array: its vertices get a
// unit tangent orthogonal to their normal, w = 1; the normal-mapped one keeps its own.
TEST_F(TangentLoader, PrimitivesWithoutANormalMapGetSomeOrthogonalTangent) {
  Gltf g = quad({}, true);
  g.push("materials", json::object());
  g.doc["meshes"][0]["primitives"].push_back(
      quad_primitive(g, 1, std::vector<vec3>(4, glm::normalize(vec3(1, 0, 1)))));
  const Scene s = load(g.write_gltf(dir / "mixed.gltf"));
  ASSERT_EQ(s.positions.size(), 8u);
  ASSERT_EQ(s.tangents.size(), 8u);
  for (std::size_t v = 0; v < 8; ++v) {
    const bool mapped = s.material_of(v < 4 ? 0 : 2).normal_texture >= 0;
    EXPECT_EQ(mapped, v < 4);
    EXPECT_NEAR(glm::length(vec3(s.tangents[v])), 1.0f, 1e-6f);
    EXPECT_NEAR(glm::dot(vec3(s.tangents[v]), s.normals[v]), 0.0f, 1e-6f);
    EXPECT_EQ(s.tangents[v].w, 1.0f);
  }
}

// A strip of two quads with u mirrored at x = 1/2: the two seam vertices are copied (8
// vertices), the left corners get (-1, 0, 0, -1), the right ones (1, 0, 0, 1). Without NORMAL
// the primitive is de-indexed (12 vertices) and gets the same tangents.
TEST_F(TangentLoader, AMirroredSeamCopiesItsVertices) {
  const std::vector<vec3> strip{{0, 0, 0}, {0.5f, 0, 0}, {1, 0, 0},
                                {0, 1, 0}, {0.5f, 1, 0}, {1, 1, 0}};
  const std::vector<std::uint16_t> indices{0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4};
  for (const bool with_normals : {true, false}) {
    Gltf g = quad({}, true);
    json& p = g.doc["meshes"][0]["primitives"][0];
    p["attributes"] = {{"POSITION", g.positions(strip)}};
    if (with_normals) p["attributes"]["NORMAL"] = g.vec3s(std::vector<vec3>(6, vec3(0, 0, 1)));
    p["attributes"]["TEXCOORD_0"] =
        g.vec2s({{0.5f, 1}, {0, 1}, {0.5f, 1}, {0.5f, 0}, {0, 0}, {0.5f, 0}});
    p["indices"] = g.indices(indices);
    const Scene s = load(g.write_gltf(dir / "strip.gltf"));
    EXPECT_EQ(s.positions.size(), with_normals ? 8u : 12u);
    ASSERT_EQ(s.tangents.size(), s.positions.size());
    for (const glm::uvec3& t : s.triangles) {
      const float cx = (s.positions[t.x].x + s.positions[t.y].x + s.positions[t.z].x) / 3;
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(s.tangents[t[c]], cx > 0.5f ? vec4(1, 0, 0, 1) : vec4(-1, 0, 0, -1));
    }
  }
}

// A rotation animation of the node turns the tangents with the normals: 90 degrees about z at
// t = 1 takes +x to +y.
TEST_F(TangentLoader, TangentsFollowANodeAnimation) {
  Gltf g = quad({}, true);
  const std::vector<float> times{0, 1};
  const float h = std::sqrt(0.5f);
  const std::vector<vec4> rotations{{0, 0, 0, 1}, {0, 0, h, h}};
  const int input = g.accessor(g.view(times.data(), sizeof(float) * 2), kFloat, 2, "SCALAR",
                               {{"min", {0}}, {"max", {1}}});
  const int output = g.accessor(g.view(rotations.data(), sizeof(vec4) * 2), kFloat, 2, "VEC4");
  g.push("animations",
         {{"samplers", {{{"input", input}, {"output", output}}}},
          {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "rotation"}}}}}}});
  Scene s = load(g.write_gltf(dir / "animated.gltf"));
  ASSERT_TRUE(s.animation);
  s.animation->pose(1.0f, s);
  for (const vec4& t : s.tangents) expect_near(t, vec4(0, 1, 0, 1), 1e-6f); // float rotation
  s.animation->pose(0.0f, s);
  for (const vec4& t : s.tangents) expect_near(t, vec4(1, 0, 0, 1), 1e-6f);
}

// A morph target with TANGENT displacements, its weight animated 0 -> 1: at weight 1 the
// tangent (1, 0, 0) + (-1, 1, 0) = (0, 1, 0).
TEST_F(TangentLoader, TangentsFollowMorphTargets) {
  Gltf g = quad({}, true, std::vector<vec4>(4, vec4(1, 0, 0, 1)));
  json& p = g.doc["meshes"][0]["primitives"][0];
  p["targets"] = {{{"POSITION", g.vec3s(std::vector<vec3>(4, vec3(0.0f)))},
                   {"TANGENT", g.vec3s(std::vector<vec3>(4, vec3(-1, 1, 0)))}}};
  g.doc["meshes"][0]["weights"] = {0.0};
  const std::vector<float> times{0, 1}, weights{0, 1};
  const int input = g.accessor(g.view(times.data(), sizeof(float) * 2), kFloat, 2, "SCALAR",
                               {{"min", {0}}, {"max", {1}}});
  const int output = g.accessor(g.view(weights.data(), sizeof(float) * 2), kFloat, 2, "SCALAR");
  g.push("animations",
         {{"samplers", {{{"input", input}, {"output", output}}}},
          {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}}}});
  Scene s = load(g.write_gltf(dir / "morph.gltf"));
  ASSERT_TRUE(s.animation);
  for (const vec4& t : s.tangents) EXPECT_EQ(t, vec4(1, 0, 0, 1));
  s.animation->pose(1.0f, s);
  for (const vec4& t : s.tangents) expect_near(t, vec4(0, 1, 0, 1), 1e-6f); // float morph
}

} // namespace
