// The distant environment (core/environment/environment.h) against what the test computes itself:
//  - orientation: where a map's texels land (Blender's equirectangular world texture with +Y up:
//    the centre column at the middle row is +X, u = 0.75 is +Z, u = 0.25 is -Z, the top row +Y),
//    and map_coordinates / map_direction as inverses;
//  - importance sampling: sample() agrees with pdf() and radiance(), lum(L)/pdf = S for every
//    sample, the texel histogram follows P_ij = lum_ij Omega_ij / S (chi-square), directions are
//    uniform within a texel, and the Monte Carlo irradiance matches a quadrature of the map;
//  - rotation: a map rotated by 2 pi k / W looks up what the map with its columns shifted k to
//    the left does.
// Rendered with the environment: test_environment_lighting.cpp.
#include "core/environment/environment.h"
#include "tests/environment_maps.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <random>
#include <vector>

namespace irad {
namespace IRAD_UNITY_ID {

using namespace env_test;

// --- 1. Orientation -------------------------------------------------------------------------

TEST(EnvironmentOrientation, NamedDirections) {
  // The closed forms: (u, v) of the axes.
  const glm::vec2 x = Environment::map_coordinates({1, 0, 0});
  const glm::vec2 z = Environment::map_coordinates({0, 0, 1});
  const glm::vec2 mz = Environment::map_coordinates({0, 0, -1});
  EXPECT_FLOAT_EQ(x.x, 0.5f);
  EXPECT_FLOAT_EQ(x.y, 0.5f);
  EXPECT_FLOAT_EQ(z.x, 0.75f);
  EXPECT_FLOAT_EQ(z.y, 0.5f);
  EXPECT_FLOAT_EQ(mz.x, 0.25f);
  EXPECT_FLOAT_EQ(mz.y, 0.5f);
  EXPECT_FLOAT_EQ(Environment::map_coordinates({0, 1, 0}).y, 0.0f);
  EXPECT_FLOAT_EQ(Environment::map_coordinates({0, -1, 0}).y, 1.0f);
  const auto near = [](const glm::vec3& a, const glm::vec3& b) {
    return glm::length(a - b) < 1e-6f;
  };
  EXPECT_TRUE(near(Environment::map_direction(0.5, 0.5), {1, 0, 0}));
  EXPECT_TRUE(near(Environment::map_direction(0.75, 0.5), {0, 0, 1}));
  EXPECT_TRUE(near(Environment::map_direction(0.25, 0.5), {0, 0, -1}));
  EXPECT_TRUE(near(Environment::map_direction(0.0, 0.5), {-1, 0, 0}));
  EXPECT_TRUE(near(Environment::map_direction(0.3, 0.0), {0, 1, 0}));
  EXPECT_TRUE(near(Environment::map_direction(0.3, 1.0), {0, -1, 0}));
}

// One bright texel at a time, around each horizontal axis: the four texels that meet at the
// axis's point of the middle row are told apart by nudging the direction 0.1 rad into each.
// Going right in the image (u up) from +X turns toward +Z, from +Z toward -X, from -Z toward +X,
// from -X toward -Z; going down (v up) turns toward -Y.
TEST(EnvironmentOrientation, BrightTexelLandsWhereTheConventionSays) {
  constexpr int w = 16, h = 8;
  struct Axis {
    const char* name;
    glm::vec3 axis;
    int column; // the column whose left edge is the axis
    glm::vec3 right;
  };
  const Axis axes[] = {{"+X", {1, 0, 0}, w / 2, {0, 0, 1}},
                       {"+Z", {0, 0, 1}, 3 * w / 4, {-1, 0, 0}},
                       {"-Z", {0, 0, -1}, w / 4, {1, 0, 0}},
                       {"-X", {-1, 0, 0}, 0, {0, 0, -1}}};
  const glm::vec3 down(0, -1, 0);
  for (const Axis& a : axes)
    for (int right = 0; right < 2; ++right)
      for (int lower = 0; lower < 2; ++lower) {
        Image map = black_map(w, h);
        const int column = ((a.column - 1 + right) % w + w) % w, row = h / 2 - 1 + lower;
        map.at(column, row) = glm::vec4(7.0f, 7.0f, 7.0f, 1.0f);
        const Environment env(map, 1.0f, 0.0f, "one texel");
        for (int r2 = 0; r2 < 2; ++r2)
          for (int l2 = 0; l2 < 2; ++l2) {
            const glm::vec3 d = glm::normalize(
                a.axis + 0.1f * ((r2 ? 1.0f : -1.0f) * a.right + (l2 ? 1.0f : -1.0f) * down));
            const float expected = (r2 == right && l2 == lower) ? 7.0f : 0.0f;
            EXPECT_EQ(env.radiance(d).g, expected)
                << a.name << ": texel (" << column << ", " << row << ") seen nudged "
                << (r2 ? "right" : "left") << ", " << (l2 ? "down" : "up");
          }
      }
  // The top row is the zenith +Y (every azimuth), the bottom row the nadir.
  Image top = black_map(w, h), bottom = black_map(w, h);
  for (int x = 0; x < w; ++x) {
    top.at(x, 0) = glm::vec4(1.0f);
    bottom.at(x, h - 1) = glm::vec4(1.0f);
  }
  const Environment up(top, 1.0f, 0.0f, "top row"), nadir(bottom, 1.0f, 0.0f, "bottom row");
  for (int k = 0; k < 32; ++k) {
    const double a = 2.0 * kPi * (k + 0.5) / 32;
    const glm::vec3 side(static_cast<float>(std::cos(a)), 0.0f, static_cast<float>(std::sin(a)));
    EXPECT_EQ(up.radiance(glm::normalize(glm::vec3(0, 1, 0) + 0.1f * side)).r, 1.0f);
    EXPECT_EQ(up.radiance(glm::normalize(glm::vec3(0, -1, 0) + 0.1f * side)).r, 0.0f);
    EXPECT_EQ(nadir.radiance(glm::normalize(glm::vec3(0, -1, 0) + 0.1f * side)).r, 1.0f);
    EXPECT_EQ(nadir.radiance(glm::normalize(glm::vec3(0, 1, 0) + 0.1f * side)).r, 0.0f);
  }
}

TEST(EnvironmentOrientation, CoordinatesAndDirectionsAreInverse) {
  std::mt19937_64 rng(12);
  double worst_direction = 0.0, worst_uv = 0.0, worst_length = 0.0;
  std::uniform_real_distribution<double> u01(0.0, 1.0), v_band(0.01, 0.99);
  for (int k = 0; k < 20000; ++k) {
    const glm::vec3 d = uniform_direction(rng);
    const glm::vec2 uv = Environment::map_coordinates(d);
    ASSERT_GE(uv.x, 0.0f);
    ASSERT_LE(uv.x, 1.0f);
    const glm::vec3 back = Environment::map_direction(uv.x, uv.y);
    worst_direction = std::max(worst_direction, double(glm::length(back - d)));
    // (u, v) -> d -> (u, v), away from the poles where u is ill-conditioned.
    const double u = u01(rng), v = v_band(rng);
    const glm::vec3 e = Environment::map_direction(u, v);
    worst_length = std::max(worst_length, std::abs(double(glm::length(e)) - 1.0));
    const glm::vec2 uv2 = Environment::map_coordinates(e);
    const double du = std::abs(uv2.x - u);
    worst_uv = std::max({worst_uv, std::min(du, 1.0 - du), std::abs(uv2.y - v)});
  }
  std::printf("round trips: |d - dir(coord(d))| <= %.2g, |uv - coord(dir(uv))| <= %.2g, "
              "| |dir| - 1 | <= %.2g\n",
              worst_direction, worst_uv, worst_length);
  // Measured: 1.6e-6 (near the poles: v comes from acos(d.y) alone, so the float direction's
  // own distance from the unit sphere, ~6e-8, moves theta by ~6e-8 / sin theta), 2.8e-7, 6e-8.
  EXPECT_LT(worst_direction, 1e-5);
  EXPECT_LT(worst_uv, 1e-5);
  EXPECT_LT(worst_length, 1e-6);
}

// --- 2. Importance sampling -------------------------------------------------------------------

constexpr int kW = 32, kH = 16;

// (a) Every sample is a unit direction whose pdf and radiance are what pdf() and radiance() say
// there, and carries luminance S: lum(L)/pdf = S (texel-constant density). Directions within
// 1e-3 texel of a border are skipped (the lookup may fall on the neighbour in float).
TEST(EnvironmentSampling, SamplesAgreeWithLookups) {
  for (const float rotation : {0.0f, 0.7f}) {
    const Environment env(random_map(kW, kH, 3), 1.5f, rotation, "random");
    ASSERT_FALSE(env.black());
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u01(0.0, 1.0);
    int skipped = 0;
    double worst_ratio = 0.0, worst_length = 0.0;
    for (int k = 0; k < 20000; ++k) {
      const EnvironmentSample s = env.sample(u01(rng), u01(rng));
      worst_length = std::max(worst_length, std::abs(double(glm::length(s.direction)) - 1.0));
      ASSERT_GT(s.pdf, 0.0);
      ASSERT_GT(luminance(s.radiance), 0.0f) << "a sample in a black texel";
      worst_ratio = std::max(worst_ratio,
                             std::abs(luminance(s.radiance) / s.pdf / env.total_luminance() - 1.0));
      if (texel_at(rotate_y(s.direction, -rotation), kW, kH).border < 1e-3) {
        ++skipped;
        continue;
      }
      EXPECT_EQ(env.pdf(s.direction), s.pdf);
      EXPECT_EQ(env.radiance(s.direction), s.radiance);
    }
    std::printf("rotation %.1f: | |d| - 1 | <= %.2g, |lum(L)/pdf/S - 1| <= %.2g, %d of 20000 "
                "near a border\n",
                rotation, worst_length, worst_ratio, skipped);
    // Measured: 1.2e-7, 2.2e-16 (the sample's pdf is lum(L)/S with the same float lum), 90 of
    // 20000 near a border at either rotation (within 1e-3 texel of 4 borders: ~0.4 %).
    EXPECT_LT(worst_length, 1e-6);
    EXPECT_LT(worst_ratio, 1e-4);
  }
}

// S and the texel probabilities from the map, computed here: S = sum lum_ij Omega_ij.
struct Reference {
  std::vector<double> probability; // P_ij, row-major
  double total = 0.0;              // S
};
Reference reference(const Image& map, float strength) {
  Reference r;
  double solid_angle = 0.0;
  for (int y = 0; y < map.height(); ++y)
    for (int x = 0; x < map.width(); ++x) {
      const double omega = texel_solid_angle(y, map.width(), map.height());
      const double p = rec709(glm::dvec3(map.at(x, y))) * strength * omega;
      r.probability.push_back(p);
      r.total += p;
      solid_angle += omega;
    }
  EXPECT_NEAR(solid_angle, 4.0 * kPi, 1e-12);
  for (double& p : r.probability) p /= r.total;
  return r;
}

// (b) The histogram of 200k samples over the texels (binned by direction, not by the sampler's
// choice) against P_ij: black texels get none, and chi-square over the others is what chance
// gives (dof = texels - 1; mean dof, standard deviation sqrt(2 dof)). Within a texel the
// fractions of phi and cos theta across it are uniform (10 bins each).
TEST(EnvironmentSampling, HistogramFollowsLuminanceTimesSolidAngle) {
  const Image map = random_map(kW, kH, 3);
  const Environment env(map, 1.5f, 0.0f, "random");
  const Reference ref = reference(map, 1.5f);
  EXPECT_NEAR(env.total_luminance() / ref.total, 1.0, 1e-6);

  constexpr int n = 200000;
  std::vector<int> count(kW * kH, 0), phi_bins(10, 0), cos_bins(10, 0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int k = 0; k < n; ++k) {
    const EnvironmentSample s = env.sample(u01(rng), u01(rng));
    const TexelAt t = texel_at(s.direction, kW, kH);
    ++count[t.y * kW + t.x];
    const glm::vec2 uv = Environment::map_coordinates(s.direction);
    const double fphi = double(uv.x) * kW - t.x;
    const double c0 = std::cos(kPi * t.y / kH), c1 = std::cos(kPi * (t.y + 1) / kH);
    const double fcos = (double(s.direction.y) - c0) / (c1 - c0);
    ++phi_bins[std::clamp(static_cast<int>(fphi * 10), 0, 9)];
    ++cos_bins[std::clamp(static_cast<int>(fcos * 10), 0, 9)];
  }
  double chi2 = 0.0, smallest_expected = 1e30;
  int dof = -1, black = 0;
  for (std::size_t i = 0; i < count.size(); ++i) {
    const double expected = n * ref.probability[i];
    if (expected == 0.0) {
      EXPECT_EQ(count[i], 0) << "black texel " << i;
      ++black;
      continue;
    }
    smallest_expected = std::min(smallest_expected, expected);
    chi2 += (count[i] - expected) * (count[i] - expected) / expected;
    ++dof;
  }
  double chi2_phi = 0.0, chi2_cos = 0.0;
  for (int b = 0; b < 10; ++b) {
    chi2_phi += (phi_bins[b] - n / 10.0) * (phi_bins[b] - n / 10.0) / (n / 10.0);
    chi2_cos += (cos_bins[b] - n / 10.0) * (cos_bins[b] - n / 10.0) / (n / 10.0);
  }
  std::printf("texel histogram: chi2 %.1f for %d dof (z = %+.2f), %d black texels, smallest "
              "expected count %.1f; within texels: chi2 %.1f (phi), %.1f (cos theta), 9 dof\n",
              chi2, dof, (chi2 - dof) / std::sqrt(2.0 * dof), black, smallest_expected, chi2_phi,
              chi2_cos);
  // Measured: chi2 337.5 for 343 dof (z = -0.21), 168 black texels, smallest expected count
  // 15.7; within texels chi2 4.1 (phi) and 8.1 (cos theta). The bounds: z < 5 (P_ij without
  // Omega, i.e. uniform in (u, v), would be off by the rows' sin theta: z in the thousands),
  // chi2(9) < 30 (p ~ 4e-4).
  EXPECT_GT(black, 0);
  EXPECT_LT((chi2 - dof) / std::sqrt(2.0 * dof), 5.0);
  EXPECT_LT(chi2_phi, 30.0);
  EXPECT_LT(chi2_cos, 30.0);
}

// (c) The irradiance on a tilted plane, E(n) = integral of L(w) max(0, n.w) dw, estimated from
// the samples (mean of L/pdf cos+) and summed directly: sum_ij L_ij * (quadrature over the
// texel of cos+, 32 x 32 cells in (phi, cos theta), equal solid angle each).
TEST(EnvironmentSampling, MonteCarloIrradianceMatchesQuadrature) {
  const Image map = random_map(kW, kH, 3);
  const Environment env(map, 1.5f, 0.0f, "random");
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.3, 0.8, -0.5));

  const auto quadrature = [&](int cells) {
    glm::dvec3 e(0.0);
    for (int y = 0; y < kH; ++y) {
      const double c0 = std::cos(kPi * y / kH), c1 = std::cos(kPi * (y + 1) / kH);
      for (int x = 0; x < kW; ++x) {
        const glm::dvec3 l = 1.5 * glm::dvec3(map.at(x, y));
        if (l == glm::dvec3(0.0)) continue;
        double integral = 0.0;
        for (int a = 0; a < cells; ++a)
          for (int b = 0; b < cells; ++b) {
            const double cos_t = c0 + (c1 - c0) * (b + 0.5) / cells;
            const double phi = 2.0 * kPi * ((x + (a + 0.5) / cells) / kW - 0.5);
            const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
            const glm::dvec3 w(sin_t * std::cos(phi), cos_t, sin_t * std::sin(phi));
            integral += std::max(0.0, glm::dot(n, w));
          }
        e += l * integral * texel_solid_angle(y, kW, kH) / double(cells * cells);
      }
    }
    return e;
  };
  const glm::dvec3 exact = quadrature(32), finer = quadrature(64);

  constexpr int samples = 200000;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  glm::dvec3 sum(0.0), sum2(0.0);
  for (int k = 0; k < samples; ++k) {
    const EnvironmentSample s = env.sample(u01(rng), u01(rng));
    const glm::dvec3 f =
        glm::dvec3(s.radiance) / s.pdf * std::max(0.0, glm::dot(n, glm::dvec3(s.direction)));
    sum += f;
    sum2 += f * f;
  }
  const glm::dvec3 mean = sum / double(samples);
  const glm::dvec3 sigma = glm::sqrt((sum2 / double(samples) - mean * mean) / double(samples));
  for (int c = 0; c < 3; ++c) {
    const double z = (mean[c] - exact[c]) / sigma[c];
    std::printf("irradiance channel %d: quadrature %.6f (64x64 cells: %+.1e relative), Monte Carlo "
                "%.6f +- %.6f (z = %+.2f)\n",
                c, exact[c], finer[c] / exact[c] - 1.0, mean[c], sigma[c], z);
    // Measured: the 32x32 quadrature within 1.2e-7 .. 5.0e-7 of the 64x64 one; z = -1.30,
    // -1.08, -1.40 (the channels share their samples, so their z move together).
    EXPECT_LT(std::abs(finer[c] / exact[c] - 1.0), 1e-4);
    EXPECT_LT(std::abs(z), 4.0);
  }
}

// (d) A black map: nothing to sample, zero density everywhere.
TEST(EnvironmentSampling, BlackMap) {
  const Environment env(black_map(8, 4), 1.0f, 0.3f, "black");
  EXPECT_TRUE(env.black());
  EXPECT_EQ(env.total_luminance(), 0.0);
  EXPECT_EQ(env.mean_radiance_integral(), 0.0);
  const EnvironmentSample s = env.sample(0.3, 0.7);
  EXPECT_EQ(s.pdf, 0.0);
  EXPECT_EQ(s.radiance, glm::vec3(0.0f));
  EXPECT_EQ(env.pdf({0, 1, 0}), 0.0);
  EXPECT_EQ(env.pdf(glm::normalize(glm::vec3(1, -2, 3))), 0.0);
  EXPECT_EQ(env.radiance({1, 0, 0}), glm::vec3(0.0f));
  // Strength 0 blackens a bright map the same way.
  EXPECT_TRUE(Environment(random_map(8, 4, 1), 0.0f, 0.0f, "dark").black());
}

// --- 3. Rotation ------------------------------------------------------------------------------

// core/environment/environment.h: "a rotation by 360/W degrees shifts the image one column to the
// left". So Environment(map, 2 pi k / W) looks up, everywhere, what Environment(shift_left(map, k),
// 0) does (the direction seen in column c of the rotated one shows column c + k of the map); the
// opposite shift does not.
TEST(EnvironmentRotation, RotationShiftsTheImageLeft) {
  const Image map = random_map(kW, kH, 21);
  for (const int k : {1, 5, -3}) {
    const float rotation = static_cast<float>(2.0 * kPi * k / kW);
    const Environment rotated(map, 1.0f, rotation, "rotated");
    const Environment left(shift_left(map, k), 1.0f, 0.0f, "shifted left");
    const Environment right(shift_left(map, -k), 1.0f, 0.0f, "shifted right");
    std::mt19937_64 rng(33);
    int compared = 0, right_differs = 0;
    for (int t = 0; t < 20000; ++t) {
      const glm::vec3 w = uniform_direction(rng);
      if (texel_at(w, kW, kH).border < 1e-3) continue;
      ++compared;
      ASSERT_EQ(rotated.radiance(w), left.radiance(w)) << "k = " << k;
      ASSERT_NEAR(rotated.pdf(w), left.pdf(w), 1e-12 * left.pdf(w));
      right_differs += rotated.radiance(w) != right.radiance(w);
    }
    std::printf("rotation by %d columns: %d directions agree with the map shifted left; %.0f %% "
                "differ from it shifted right\n",
                k, compared, 100.0 * right_differs / compared);
    EXPECT_GT(right_differs, compared / 2);
  }
}

} // namespace
} // namespace irad
