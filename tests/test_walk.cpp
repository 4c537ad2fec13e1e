// The quasi-random walk against its definition (design.md section 1).
#include "core/lights/light_sampler.h"
#include "core/sampling/particle_counts.h"
#include "core/scene/scene_builder.h"
#include "core/util/error.h"
#include "walk/vpls/quasi_random_walk.h"

#include <gtest/gtest.h>
#include <numbers>

namespace irad {
namespace IRAD_UNITY_ID {

constexpr double pi = std::numbers::pi;

// Radiant power of a VPL's emission profile: pi I (surface), 2 pi I (two-sided), 4 pi I (point).
double vpl_power(const Vpl& v) {
  const double mean = (v.intensity.x + v.intensity.y + v.intensity.z) / 3.0;
  switch (v.kind) {
  case VplKind::Surface:
    return pi * mean;
  case VplKind::TwoSided:
    return 2.0 * pi * mean;
  case VplKind::Point:
    return 4.0 * pi * mean;
  case VplKind::Spot:
  case VplKind::Directional:
    break;
  }
  return 0.0;
}

double depth0_power(const VplSet& set) {
  double sum = 0.0;
  for (const Vpl& v : set.vpls)
    if (v.depth == 0) sum += vpl_power(v);
  return sum;
}

TEST(QuasiRandomWalk, Depth0PowerEqualsEmitterPower) {
  Log log([](const std::string&) {});
  // Two emitters of different radiance and size, one double-sided, and a point light.
  Scene s = closed_box(1.0f, 0.5f, 0.2f, 3.0f);
  const std::uint32_t bright = add_material(s, glm::vec3(0.5f), glm::vec3(10.0f), true);
  add_quad(s, {0.1f, 0.1f, 0.5f}, {0.2f, 0.1f, 0.5f}, {0.2f, 0.3f, 0.5f}, {0.1f, 0.3f, 0.5f},
           bright);
  PunctualLight point;
  point.position = {0.5f, 0.5f, 0.5f};
  point.intensity = {1.0f, 2.0f, 3.0f};
  s.lights.push_back(point);
  finish(s);
  // Phi = pi A L (one side) for the ceiling patch, 2 pi A L for the double-sided one, 4 pi I.
  const double expected = pi * 0.04 * 3.0 + 2.0 * pi * 0.02 * 10.0 + 4.0 * pi * 2.0;
  EXPECT_NEAR(LightSampler(s).total_power(), expected, 1e-6 * expected); // float vertices
  const RayScene rays(s);
  for (std::uint32_t n : {1u, 7u, 256u, 1000u}) {
    const VplSet set = quasi_random_walk(s, rays, {n, 64}, log);
    // Each depth-0 VPL carries Phi/N exactly (uniform radiance per emitter); float rounding only.
    EXPECT_NEAR(depth0_power(set), expected, 1e-5 * expected) << n;
  }
}

TEST(QuasiRandomWalk, ClosedBoxReachesLmaxAndCountsMatch) {
  Log log([](const std::string&) {});
  const Scene s = closed_box(2.0f, 0.6f, 0.5f, 1.0f);
  const RayScene rays(s);
  for (std::uint32_t n : {1u, 16u, 64u, 333u, 1024u}) {
    const VplSet set = quasi_random_walk(s, rays, {n, 64}, log);
    const ParticleCounts counts(n, mean_albedo(s), 64);
    EXPECT_EQ(set.l_max, counts.l_max());
    int deepest = 0;
    std::vector<std::uint64_t> per_depth(static_cast<std::size_t>(set.l_max) + 1, 0);
    for (const Vpl& v : set.vpls) {
      deepest = std::max<int>(deepest, v.depth);
      ++per_depth[v.depth];
      EXPECT_TRUE(std::isfinite(v.intensity.x) && std::isfinite(v.intensity.y) &&
                  std::isfinite(v.intensity.z));
    }
    // Nothing escapes a closed box: every particle reaches D(i), so n_j VPLs at depth j.
    EXPECT_EQ(deepest, set.l_max) << n;
    for (int j = 0; j <= set.l_max; ++j) EXPECT_EQ(per_depth[j], counts.reaching(j)) << n;
    EXPECT_EQ(set.vpls.size(), counts.vpl_count());
  }
}

// rho_bar estimates the transport norm; in a closed box of uniform albedo the mean depth-j power
// falls exactly as rho^j: sum over depth-j VPLs of pi*I equals rho^j Phi (for a uniform albedo the
// throughput is deterministic).
TEST(QuasiRandomWalk, PowerPerDepthFallsWithAlbedoInAClosedBox) {
  Log log([](const std::string&) {});
  const float rho = 0.5f;
  const Scene s = closed_box(1.0f, rho, 0.3f, 2.0f);
  const RayScene rays(s);
  const VplSet set = quasi_random_walk(s, rays, {4096, 64}, log);
  const double phi = LightSampler(s).total_power();
  std::vector<double> power(static_cast<std::size_t>(set.l_max) + 1, 0.0);
  for (const Vpl& v : set.vpls) power[v.depth] += vpl_power(v);
  for (int j = 0; j <= set.l_max; ++j)
    EXPECT_NEAR(power[j], phi * std::pow(rho, j), 1e-4 * phi) << "depth " << j;
}

TEST(QuasiRandomWalk, RefusesNoLightAndZeroPaths) {
  Log log([](const std::string&) {});
  Scene s = closed_box(1.0f, 0.5f, 0.2f, 1.0f);
  const RayScene rays(s);
  EXPECT_THROW(quasi_random_walk(s, rays, {0, 64}, log), Error);
  s.materials[1].emission = glm::vec3(0.0f);
  EXPECT_THROW(quasi_random_walk(s, rays, {16, 64}, log), Error);
}

TEST(QuasiRandomWalk, AlbedoOneIsCappedWithAWarningAndStaysFinite) {
  int warnings = 0;
  Log log([&](const std::string&) { ++warnings; });
  const Scene s = closed_box(1.0f, 1.0f, 0.3f, 1.0f);
  const RayScene rays(s);
  const VplSet set = quasi_random_walk(s, rays, {8, 12}, log);
  EXPECT_TRUE(set.depth_capped);
  EXPECT_EQ(set.l_max, 12);
  EXPECT_EQ(warnings, 1);
  for (const Vpl& v : set.vpls) EXPECT_TRUE(std::isfinite(v.intensity.x));
}

} // namespace IRAD_UNITY_ID
} // namespace irad
