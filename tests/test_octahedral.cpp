// Normals in 4 bytes on the GPU (raster/scene/octahedral.h): every direction comes back within
// 6.4e-5 radians (a million random directions), the axes exactly, and the G-buffer holds what the
// C++ decoding gives.
#include "raster/context/gl_context.h"
#include "raster/scene/octahedral.h"
#include "tests/height_field.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <random>

namespace irad {
namespace IRAD_UNITY_ID {

using namespace test_support;

// The angle between unit vectors a and b, accurate for small angles.
double angle(const glm::vec3& a, const glm::vec3& b) {
  const glm::dvec3 x(a), y(b);
  return 2.0 * std::asin(std::min(1.0, glm::length(x - y) / 2.0));
}

// A direction from two uniform numbers (uniform over the sphere).
glm::vec3 direction(double u, double v) {
  const double z = 2.0 * u - 1.0, r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 6.283185307179586 * v;
  return glm::normalize(glm::vec3(glm::dvec3(r * std::cos(phi), r * std::sin(phi), z)));
}

TEST(Octahedral, EveryDirectionComesBackClose) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  double worst = 0.0;
  for (int i = 0; i < 1000000; ++i) {
    const glm::vec3 n = direction(uniform(random), uniform(random));
    worst = std::max(worst, angle(gl::octahedral_decode(gl::octahedral_encode(n)), n));
  }
  std::printf("largest angle over a million directions: %.3g rad\n", worst);
  EXPECT_LT(worst, 7e-5); // measured: 6.4e-5
}

TEST(Octahedral, AxesComeBackExactly) {
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {1.0f, -1.0f}) {
      glm::vec3 n(0.0f);
      n[axis] = sign;
      EXPECT_EQ(gl::octahedral_decode(gl::octahedral_encode(n)), n);
    }
  // A zero vector (no direction) encodes as +z rather than as NaN.
  EXPECT_EQ(gl::octahedral_decode(gl::octahedral_encode(glm::vec3(0.0f))), glm::vec3(0, 0, 1));
}

TEST(Octahedral, TheGBufferHoldsTheDecodedNormals) {
  // 8 x 8 quads facing the camera, each with a normal of its own on all four corners (the six
  // axes, then random directions of both hemispheres): a fragment's normal is that normal.
  Scene s;
  const std::uint32_t m = add_material(s, glm::vec3(0.5f));
  std::vector<glm::vec3> normals;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int i = 0; i < 64; ++i) {
    glm::vec3 n = direction(uniform(random), uniform(random));
    if (i < 6) n = glm::vec3(0.0f), n[i / 2] = i % 2 ? -1.0f : 1.0f;
    normals.push_back(n);
    const float x = -1.0f + 0.25f * float(i % 8), y = -1.0f + 0.25f * float(i / 8);
    add_quad(s, {x, y, 0}, {x + 0.25f, y, 0}, {x + 0.25f, y + 0.25f, 0}, {x, y + 0.25f, 0}, m);
    for (std::size_t k = s.normals.size() - 4; k < s.normals.size(); ++k) s.normals[k] = n;
  }
  s.cameras.push_back(look_at({0.0f, 0.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 0.8f));
  finish(s);
  const View view = make_view(s.cameras[0], s.bounds, 128, 128);
  const auto context = gl::create_osmesa_context();
  const gl::CurrentScope current(*context);
  const gl::GpuScene gpu(context->api(), s);
  const GBufferPixels g = draw_gbuffer(context->api(), gpu, view, nullptr);
  std::size_t covered = 0;
  double worst_cpu = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < g.position.size(); ++i) {
    if (g.position[i].w == 0.0f) continue;
    ++covered;
    const int col = std::clamp(int(std::floor((g.position[i].x + 1.0f) * 4.0f)), 0, 7);
    const int row = std::clamp(int(std::floor((g.position[i].y + 1.0f) * 4.0f)), 0, 7);
    const glm::vec3 n = normals[std::size_t(row * 8 + col)], got(g.normal[i]);
    worst_cpu = std::max(worst_cpu, angle(got, gl::octahedral_decode(gl::octahedral_encode(n))));
    worst = std::max(worst, angle(got, n));
    if (row * 8 + col < 6) {
      EXPECT_EQ(got, n);
    }
  }
  std::printf("%zu pixels: largest angle to the C++ decoding %.3g, to the normal %.3g rad\n",
              covered, worst_cpu, worst);
  EXPECT_GT(covered, g.position.size() / 4);
  EXPECT_LT(worst_cpu, 1e-6); // float rounding apart (measured: 1.9e-7)
  EXPECT_LT(worst, 7e-5);     // measured: 5.3e-5
}

} // namespace IRAD_UNITY_ID
} // namespace irad
