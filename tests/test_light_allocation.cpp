// Lights by power (design.md 6.2): the walk's N paths are shared among the lights in proportion
// to their power, stratified by the walk's first Halton dimension (core/lights/light_sampler.h),
// against the seed's uniform share (each of the G lights N/G paths, beta_0 divided by P(k) = 1/G
// instead). On a room with one strong and many weak lights, power allocation must come closer to
// the path tracer at equal N.
#include "core/camera/view.h"
#include "core/image/image_io.h"
#include "core/image/image_metrics.h"
#include "core/lights/light_sampler.h"
#include "core/scene/scene_builder.h"
#include "tests/side_by_side.h"
#include "walk/estimators/path_tracer.h"
#include "walk/estimators/vpl_tracer.h"
#include "walk/vpls/quasi_random_walk.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <gtest/gtest.h>
#include <numbers>
#include <string>
#include <vector>

namespace irad {
namespace IRAD_UNITY_ID {

constexpr double pi = std::numbers::pi;

Log quiet_log() {
  return Log([](const std::string&) {});
}

struct ManyLights {
  Scene scene;
  std::vector<glm::vec3> centres; // of every light: the strong patch, the weak patches, the points
  std::vector<double> power;      // Phi of each
};

// The closed 2 m box of core/scene/scene_builder.h with its 0.5 m ceiling patch (radiance 8: 6.3
// W), eight 0.1 m patches of radiance 2 on the walls (0.063 W each) and four point lights of
// intensity 0.02 (0.25 W each): 13 lights, the strong one 77 % of the power.
ManyLights many_lights() {
  ManyLights m;
  m.scene = closed_box(2.0f, 0.5f, 0.5f, 8.0f);
  m.centres.push_back({1.0f, 2.0f, 1.0f});
  m.power.push_back(pi * 0.25 * 8.0);
  for (int k = 0; k < 8; ++k) {
    // On the walls x = 0 (facing +x) and z = 0 (facing +z), at varying heights.
    const std::uint32_t mat = add_material(m.scene, glm::vec3(0.5f), glm::vec3(2.0f));
    const float a = 0.3f + 0.2f * static_cast<float>(k % 4),
                h = 0.4f + 0.3f * static_cast<float>(k / 4);
    const float e = 1e-3f; // just off the wall
    if (k % 2 == 0) {
      add_quad(m.scene, {e, h, a}, {e, h + 0.1f, a}, {e, h + 0.1f, a + 0.1f}, {e, h, a + 0.1f},
               mat);
      m.centres.push_back({e, h + 0.05f, a + 0.05f});
    } else {
      add_quad(m.scene, {a, h, e}, {a + 0.1f, h, e}, {a + 0.1f, h + 0.1f, e}, {a, h + 0.1f, e},
               mat);
      m.centres.push_back({a + 0.05f, h + 0.05f, e});
    }
    m.power.push_back(pi * 0.01 * 2.0);
  }
  for (int k = 0; k < 4; ++k) {
    PunctualLight p;
    p.position = {0.4f + 0.4f * static_cast<float>(k), 1.5f, 0.3f + 0.45f * static_cast<float>(k)};
    p.intensity = glm::vec3(0.02f);
    m.scene.lights.push_back(p);
    m.centres.push_back(p.position);
    m.power.push_back(4.0 * pi * 0.02);
  }
  m.scene.cameras.push_back(look_at({1.6f, 1.2f, 1.95f}, {0.6f, 0.8f, 0.0f}, {0, 1, 0}, 1.3f));
  finish(m.scene);
  return m;
}

std::size_t nearest(const std::vector<glm::vec3>& centres, const glm::vec3& p) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < centres.size(); ++k)
    if (glm::length(centres[k] - p) < glm::length(centres[best] - p)) best = k;
  return best;
}

// Largest |m_k(n) - n P_k| over the lights k and the prefixes n = n_j of the walk, where m_k(n)
// counts the particles i < n that start on light k.
double worst_share_deviation(const ManyLights& m, const VplSet& set, LightAllocation allocation) {
  const std::size_t lights = m.centres.size();
  std::vector<int> light_of(set.paths, -1);
  for (const Vpl& v : set.vpls)
    if (v.depth == 0) light_of[v.path] = static_cast<int>(nearest(m.centres, v.position));
  double total = 0.0;
  for (double p : m.power) total += p;
  const ParticleCounts counts(set.paths, set.rho_bar, 64);
  double worst = 0.0;
  for (int j = 0; j <= counts.l_max(); ++j) {
    const std::uint32_t n = counts.reaching(j);
    std::vector<int> m_k(lights, 0);
    for (std::uint32_t i = 0; i < n; ++i) ++m_k[static_cast<std::size_t>(light_of[i])];
    for (std::size_t k = 0; k < lights; ++k) {
      const double share = allocation == LightAllocation::Power ? m.power[k] / total
                                                                : 1.0 / static_cast<double>(lights);
      worst = std::max(worst, std::abs(m_k[k] - n * share));
    }
  }
  return worst;
}

TEST(LightAllocation, SharesFollowPowerOrAreEqualWithinTwoPaths) {
  Log log = quiet_log();
  const ManyLights m = many_lights();
  const RayScene rays(m.scene);
  for (LightAllocation a : {LightAllocation::Power, LightAllocation::Uniform})
    for (std::uint32_t n : {64u, 256u, 1000u}) {
      WalkOptions o{n, 64};
      o.allocation = a;
      const VplSet set = quasi_random_walk(m.scene, rays, o, log);
      const double worst = worst_share_deviation(m, set, a);
      std::printf("%s, N = %u: worst |m_k(n_j) - n_j P_k| = %.3f\n",
                  a == LightAllocation::Power ? "power" : "uniform", n, worst);
      // Measured: power 0.87 (N = 64 and 256), 1.55 (N = 1000); uniform 0.92, 0.92, 1.92. The
      // light is chosen by the first Halton dimension, the van der Corput sequence, whose every
      // prefix is stratified: m_k(n) stays within about 2 of n P_k for every light and prefix.
      EXPECT_LT(worst, 2.5);
    }
}

TEST(LightAllocation, PowerBeatsUniformAgainstThePathTracer) {
  Log log = quiet_log();
  const ManyLights m = many_lights();
  const RayScene rays(m.scene);
  const View view = make_view(m.scene.cameras.at(0), m.scene.bounds, 64, 64);
  const Image pt = path_trace(m.scene, rays, view, {512, 1, 0, 1000});
  double relmse[2];
  std::vector<Image> images;
  for (LightAllocation a : {LightAllocation::Power, LightAllocation::Uniform}) {
    WalkOptions o{256, 64};
    o.allocation = a;
    const VplSet set = quasi_random_walk(m.scene, rays, o, log);
    images.push_back(trace_vpls(m.scene, rays, view, set, {0.05f, 0}));
    const ImageMetrics e = compare_images(images.back(), pt);
    relmse[a == LightAllocation::Power ? 0 : 1] = e.relmse;
    std::printf("%s: relMSE %.4g, mean ratio %.4f\n",
                a == LightAllocation::Power ? "power" : "uniform", e.relmse, e.mean_ratio[1]);
  }
  const Image power_error = relative_error_image(images[0], pt, {0.2, 1});
  const Image uniform_error = relative_error_image(images[1], pt, {0.2, 1});
  maybe_write_side_by_side("allocation", {&images[0], &images[1], &pt});
  maybe_write_side_by_side("allocation_error", {&power_error, &uniform_error});
  // Measured (64 x 64, N = 256, rt-vpl, pt at 512 spp): relMSE 0.0037 (power) against 0.027
  // (uniform), 7x lower; mean ratios 0.976 and 1.014. The uniform share leaves the strong light
  // (77 % of the power) 20 of the 256 paths. Bound: at least 2x lower.
  EXPECT_LT(relmse[0], 0.5 * relmse[1]);
  EXPECT_LT(relmse[0], 0.008);
}

} // namespace IRAD_UNITY_ID
} // namespace irad
