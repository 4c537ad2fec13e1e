// The exact reduction of flat parts (core/mesh/planar/planar_reduction.h): how far it gets on flat,
// folded, closed and holed grids, and that it changes no surface: areas, the integral of the
// normal, watertightness, and heights along vertical rays on a height field with flat, sloped
// and bumpy parts against the original triangles. The same of the reduction in spatial chunks
// (core/mesh/planar/planar_chunks.h), and that its result does not depend on the threads.
#include "core/mesh/planar/flat_components.h"
#include "core/mesh/planar/planar_chunks.h"
#include "core/mesh/planar/planar_reduction.h"

#include <algorithm>
#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <map>
#include <optional>
#include <random>

namespace irad {
namespace IRAD_UNITY_ID {

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<glm::uvec3> triangles;
  std::map<std::array<float, 3>, std::uint32_t> index; // welding by position

  std::uint32_t vertex(const glm::vec3& p) {
    const auto [at, added] =
        index.try_emplace({p.x, p.y, p.z}, static_cast<std::uint32_t>(positions.size()));
    if (added) positions.push_back(p);
    return at->second;
  }
  // An n x n grid of quads over o + [0,1]^2 (u, v), counter-clockwise about u x v; `keep`
  // leaves out the quads it refuses.
  template <class Keep>
  void grid(const glm::vec3& o, const glm::vec3& u, const glm::vec3& v, int n, Keep keep) {
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        if (!keep(i, j)) continue;
        const auto at = [&](int a, int b) {
          return vertex(o + u * (float(a) / float(n)) + v * (float(b) / float(n)));
        };
        const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
        triangles.push_back({a, b, c});
        triangles.push_back({a, c, d});
      }
  }
  void grid(const glm::vec3& o, const glm::vec3& u, const glm::vec3& v, int n) {
    grid(o, u, v, n, [](int, int) { return true; });
  }
};

glm::dvec3 cross_of(const Mesh& m, const glm::uvec3& t) {
  const glm::dvec3 a(m.positions[t.x]), b(m.positions[t.y]), c(m.positions[t.z]);
  return glm::cross(b - a, c - a);
}

// The integral of the normal (half the summed cross products) and the area.
std::pair<glm::dvec3, double> moments(const Mesh& m, const std::vector<glm::uvec3>& tris) {
  glm::dvec3 normal(0.0);
  double area = 0.0;
  for (const glm::uvec3& t : tris) {
    normal += 0.5 * cross_of(m, t);
    area += 0.5 * glm::length(cross_of(m, t));
  }
  return {normal, area};
}

void expect_same_surface(const Mesh& m, const std::vector<glm::uvec3>& reduced) {
  const auto [n0, a0] = moments(m, m.triangles);
  const auto [n1, a1] = moments(m, reduced);
  // Float positions, double sums: agreement to 1e-9 of the area measured on these grids.
  EXPECT_NEAR(a1, a0, 1e-7 * a0);
  EXPECT_NEAR(glm::length(n1 - n0), 0.0, 1e-7 * a0);
}

// Directed edges each matched by the opposite one.
bool watertight(const std::vector<glm::uvec3>& tris) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const glm::uvec3& t : tris)
    for (int e = 0; e < 3; ++e) ++directed[{t[e], t[(e + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    const auto back = directed.find({edge.second, edge.first});
    if (back == directed.end() || back->second != count) return false;
  }
  return true;
}

// m reduces to `triangles` triangles in `patches` patches, the same surface.
void expect_reduced_to(const Mesh& m, std::size_t patches, std::size_t triangles) {
  const PlanarReduction r = reduce_planar(m.positions, m.triangles, 1e-6f);
  EXPECT_EQ(r.patches, patches);
  EXPECT_EQ(r.triangles.size(), triangles);
  expect_same_surface(m, r.triangles);
}

TEST(PlanarReduction, FlatGridToTwoTriangles) {
  Mesh m;
  m.grid({0, 0, 0}, {2, 0, 0}, {0, 3, 0}, 64); // 8192 triangles
  expect_reduced_to(m, 1, 2);
}

TEST(PlanarReduction, FoldKeepsItsCreaseStraight) {
  Mesh m;
  m.grid({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 32);
  m.grid({0, 0, 0}, {0, 1, 0}, {0, 0, 1}, 32); // shares the edge x = z = 0
  expect_reduced_to(m, 2, 4);
}

TEST(PlanarReduction, ClosedBoxStaysClosed) {
  Mesh m;
  const int n = 24;
  // Six faces, outward: o, u, v with u x v outward.
  m.grid({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, n); // z = 0, normal -z
  m.grid({0, 0, 1}, {1, 0, 0}, {0, 1, 0}, n); // z = 1, +z
  m.grid({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, n); // y = 0, -y
  m.grid({0, 1, 0}, {0, 0, 1}, {1, 0, 0}, n); // y = 1, +y
  m.grid({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, n); // x = 0, -x
  m.grid({1, 0, 0}, {0, 1, 0}, {0, 0, 1}, n); // x = 1, +x
  ASSERT_TRUE(watertight(m.triangles));
  const PlanarReduction r = reduce_planar(m.positions, m.triangles, 1e-6f);
  EXPECT_EQ(r.patches, 6u);
  EXPECT_EQ(r.triangles.size(), 12u);
  EXPECT_TRUE(watertight(r.triangles));
  expect_same_surface(m, r.triangles);
}

TEST(PlanarReduction, HoleStaysOpen) {
  Mesh m;
  m.grid({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 40,
         [](int i, int j) { return !(i >= 10 && i < 20 && j >= 15 && j < 30); });
  const PlanarReduction r = reduce_planar(m.positions, m.triangles, 1e-6f);
  // A square with a square hole: 8 corners, at least 8 triangles.
  EXPECT_GE(r.triangles.size(), 8u);
  EXPECT_LE(r.triangles.size(), 12u);
  expect_same_surface(m, r.triangles);
}

TEST(PlanarReduction, BackToBackFacesAreNotMerged) {
  Mesh m;
  m.grid({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 16);
  m.grid({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, 16); // the same square facing -z, same vertices
  const PlanarReduction r = reduce_planar(m.positions, m.triangles, 1e-6f);
  EXPECT_EQ(r.patches, 2u);
  std::size_t up = 0, down = 0;
  double up_area = 0.0, down_area = 0.0;
  for (const glm::uvec3& t : r.triangles) {
    const glm::dvec3 c = cross_of(m, t);
    (c.z > 0.0 ? up : down) += 1;
    (c.z > 0.0 ? up_area : down_area) += 0.5 * glm::length(c);
  }
  EXPECT_GT(up, 0u);
  EXPECT_GT(down, 0u);
  EXPECT_NEAR(up_area, 1.0, 1e-7);
  EXPECT_NEAR(down_area, 1.0, 1e-7);
}

TEST(PlanarReduction, CurvedSurfaceUnchanged) {
  Mesh m;
  const int n = 16;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto at = [&](int a, int b) {
        const float x = float(a) / float(n), y = float(b) / float(n);
        return m.vertex({x, y, 0.3f * x * x + 0.2f * y * y + 0.1f * x * y});
      };
      const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({a, c, d});
    }
  const PlanarReduction r = reduce_planar(m.positions, m.triangles, 1e-6f);
  EXPECT_EQ(r.collapses, 0u);
  EXPECT_EQ(r.triangles.size(), m.triangles.size());
}

// reduce_flat_components (core/mesh/planar/flat_components.h): a flat grid, a curved one and a flat
// grid with a curved cap (one component) side by side. The reduction runs on the flat grid and
// on the capped one, which sampling finds flat, exactly as alone; the curved grid comes out
// unchanged after them.
TEST(PlanarReduction, OnlyComponentsWithFlatPartsAreReduced) {
  Mesh flat, curved, capped, all;
  const auto bowl = [](float x, float y) { return 0.3f * x * x + 0.2f * y * y + 0.1f * x * y; };
  const auto add_curved = [&](Mesh& m, const glm::vec3& o) {
    const int n = 16;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const auto at = [&](int a, int b) {
          const float x = float(a) / float(n), y = float(b) / float(n);
          return m.vertex(o + glm::vec3(x, y, bowl(x, y)));
        };
        const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({a, c, d});
      }
  };
  for (Mesh* m : {&flat, &all}) m->grid({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 12);
  for (Mesh* m : {&curved, &all}) add_curved(*m, {3, 0, 0});
  for (Mesh* m : {&capped, &all}) {
    m->grid({6, 0, 0}, {1, 0, 0}, {0, 1, 0}, 16); // a corner shared with the cap: one component
    add_curved(*m, {6, 0, 0});
  }
  const PlanarReduction alone_flat = reduce_planar(flat.positions, flat.triangles, 1e-6f);
  ASSERT_EQ(alone_flat.triangles.size(), 2u);
  const PlanarReduction r = reduce_flat_components(all.positions, all.triangles, 1e-6f);
  // The curved grid's 512 triangles last, as they were.
  ASSERT_GT(r.triangles.size(), curved.triangles.size());
  const std::vector<glm::uvec3> tail(r.triangles.end() - 512, r.triangles.end());
  const std::vector<glm::uvec3> curved_in_all(all.triangles.begin() + 288,
                                              all.triangles.begin() + 800);
  EXPECT_EQ(tail, curved_in_all);
  // The flat and the capped components reduced as reduce_planar reduces them together.
  std::vector<glm::uvec3> reducible(all.triangles.begin(), all.triangles.begin() + 288);
  reducible.insert(reducible.end(), all.triangles.begin() + 800, all.triangles.end());
  const PlanarReduction expected = reduce_planar(all.positions, reducible, 1e-6f);
  EXPECT_EQ(std::vector<glm::uvec3>(r.triangles.begin(), r.triangles.end() - 512),
            expected.triangles);
  EXPECT_EQ(r.collapses, expected.collapses);
  EXPECT_GT(r.collapses, 0u);
  // Nothing flat at all: the triangles unchanged.
  const PlanarReduction none = reduce_flat_components(curved.positions, curved.triangles, 1e-6f);
  EXPECT_EQ(none.triangles, curved.triangles);
  EXPECT_EQ(none.collapses, 0u);
}

// The height of the surface above (x, y) along a vertical ray, if a triangle covers it.
std::optional<double> height_at(const Mesh& m, const std::vector<glm::uvec3>& tris, double x,
                                double y) {
  for (const glm::uvec3& t : tris) {
    const glm::dvec3 a(m.positions[t.x]), b(m.positions[t.y]), c(m.positions[t.z]);
    const auto side = [&](const glm::dvec3& p, const glm::dvec3& q) {
      return (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x);
    };
    const double w0 = side(b, c), w1 = side(c, a), w2 = side(a, b), sum = w0 + w1 + w2;
    if (sum <= 0.0 || w0 < 0.0 || w1 < 0.0 || w2 < 0.0) continue;
    return (w0 * a.z + w1 * b.z + w2 * c.z) / sum;
  }
  return std::nullopt;
}

// A height field over [0,1]^2 on a 48^2 grid: flat ground, a plateau with planar ramps (folds
// at every height), a bumpy hill. Every vertical ray meets the reduced surface where it met the
// original, at the same height within 2 epsilon.
Mesh height_field(int n) {
  Mesh m;
  const auto h = [](float x, float y) {
    const float plateau =
        std::clamp(0.3f - 2.0f * std::max(std::abs(x - 0.3f), std::abs(y - 0.3f)), 0.0f, 0.15f);
    const float r2 = (x - 0.75f) * (x - 0.75f) + (y - 0.7f) * (y - 0.7f);
    return plateau +
           (r2 < 0.04f ? 0.2f * (0.04f - r2) * (1.0f + 0.5f * std::sin(40.0f * x)) : 0.0f);
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto at = [&](int a, int b) {
        const float x = float(a) / float(n), y = float(b) / float(n);
        return m.vertex({x, y, h(x, y)});
      };
      const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({a, c, d});
    }
  return m;
}

// Every vertical ray over the height field meets `reduced` where it met the original, at the
// same height within 2 epsilon.
void expect_same_heights(const Mesh& m, const std::vector<glm::uvec3>& reduced, float epsilon) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.001, 0.999);
  for (int k = 0; k < 2000; ++k) {
    const double x = unit(rng), y = unit(rng);
    const std::optional<double> before = height_at(m, m.triangles, x, y);
    const std::optional<double> after = height_at(m, reduced, x, y);
    ASSERT_TRUE(before && after) << x << ", " << y;
    EXPECT_NEAR(*after, *before, 2.0 * epsilon) << x << ", " << y;
  }
}

TEST(PlanarReduction, HeightFieldKeepsEveryHeight) {
  const Mesh m = height_field(48);
  const float epsilon = 1e-6f;
  const PlanarReduction r = reduce_planar(m.positions, m.triangles, epsilon);
  std::printf("height field: %zu -> %zu triangles, %zu patches\n", m.triangles.size(),
              r.triangles.size(), r.patches);
  EXPECT_LT(r.triangles.size(), m.triangles.size() / 4);
  expect_same_surface(m, r.triangles);
  expect_same_heights(m, r.triangles, epsilon);
}

TEST(PlanarChunks, CoverEveryTriangleOnceInSmallAscendingChunks) {
  const Mesh m = height_field(48); // 4608 triangles
  const auto chunks = spatial_chunks(m.positions, m.triangles, 500, 3);
  EXPECT_EQ(chunks.size(), 16u); // 4608 halved four times: 288 each
  std::vector<int> seen(m.triangles.size(), 0);
  for (const auto& c : chunks) {
    EXPECT_LE(c.size(), 500u);
    EXPECT_TRUE(std::is_sorted(c.begin(), c.end()));
    for (std::uint32_t t : c) ++seen[t];
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(seen.size()));
  EXPECT_EQ(spatial_chunks(m.positions, m.triangles, 500, 1), chunks);
  EXPECT_EQ(spatial_chunks(m.positions, m.triangles, 5000).size(), 1u);
}

// In chunks: the same surface and heights, no more than a few triangles more than in one piece
// along the chunks' borders, the same triangles on one thread as on four; a mesh within one
// chunk is reduce_planar's.
TEST(PlanarChunks, HeightFieldKeepsEveryHeight) {
  const Mesh m = height_field(48);
  const float epsilon = 1e-6f;
  const PlanarReduction whole = reduce_planar(m.positions, m.triangles, epsilon);
  const PlanarReduction r = reduce_planar_chunked(m.positions, m.triangles, epsilon, 500, 4);
  std::printf("height field in 16 chunks: %zu -> %zu triangles (%zu in one piece)\n",
              m.triangles.size(), r.triangles.size(), whole.triangles.size());
  EXPECT_LT(r.triangles.size(), m.triangles.size() / 3);
  expect_same_surface(m, r.triangles);
  expect_same_heights(m, r.triangles, epsilon);
  const PlanarReduction one = reduce_planar_chunked(m.positions, m.triangles, epsilon, 500, 1);
  EXPECT_EQ(one.triangles, r.triangles);
  EXPECT_EQ(one.collapses, r.collapses);
  const PlanarReduction single = reduce_planar_chunked(m.positions, m.triangles, epsilon);
  EXPECT_EQ(single.triangles, whole.triangles);
}

TEST(PlanarChunks, ClosedBoxStaysClosed) {
  Mesh m;
  const int n = 40; // 19200 triangles
  m.grid({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, n);
  m.grid({0, 0, 1}, {1, 0, 0}, {0, 1, 0}, n);
  m.grid({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, n);
  m.grid({0, 1, 0}, {0, 0, 1}, {1, 0, 0}, n);
  m.grid({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, n);
  m.grid({1, 0, 0}, {0, 1, 0}, {0, 0, 1}, n);
  ASSERT_TRUE(watertight(m.triangles));
  const PlanarReduction r = reduce_planar_chunked(m.positions, m.triangles, 1e-6f, 1000, 2);
  std::printf("box in chunks: %zu -> %zu triangles\n", m.triangles.size(), r.triangles.size());
  EXPECT_TRUE(watertight(r.triangles));
  expect_same_surface(m, r.triangles);
  EXPECT_LT(r.triangles.size(), m.triangles.size() / 5); // 2240 (12 in one piece)
}

} // namespace IRAD_UNITY_ID
} // namespace irad
