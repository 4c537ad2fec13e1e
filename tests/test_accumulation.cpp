// Float accumulation of many raster passes (a hard case of the accuracy issue): 1e5 additive
// passes into the raster's RGBA32F target, against a double-precision sum of the same values.
#include "core/sampling/radical_inverse.h"
#include "raster/context/gl_context.h"
#include "raster/context/shader_program.h"
#include "raster/image/target.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace irad {
namespace IRAD_UNITY_ID {
// ---------------------------------------------------------------------------------------------
// 7. The accumulation itself: 1e5 additive passes into the raster's RGBA32F target, against a
// double-precision sum of the same float values.

TEST(HardCases, FloatAccumulationOfManyPasses) {
  const auto context = gl::create_osmesa_context();
  const GladGLContext& api = context->api();
  // A full-screen triangle from gl_VertexID, painting the uniform value.
  const gl::ShaderProgram program(
      api, "accumulate",
      "#version 330 core\n"
      "void main() {\n"
      "  vec2 p = vec2((gl_VertexID & 1) * 4 - 1, (gl_VertexID & 2) * 2 "
      "- 1);\n"
      "  gl_Position = vec4(p, 0.0, 1.0);\n"
      "}\n",
      "#version 330 core\n"
      "uniform vec4 u_value;\n"
      "out vec4 o_color;\n"
      "void main() { o_color = u_value; }\n");
  const GLint u_value = program.uniform("u_value");
  const gl::VertexArray vao = gl::make_vertex_array(api);
  const gl::Target target(api, 16, 16);

  // Values log-uniform in [1e-7, 1e-1], in a deterministic well-spread order (radical inverse).
  constexpr int passes = 100000;
  std::vector<float> values(passes);
  for (int k = 0; k < passes; ++k)
    values[k] = static_cast<float>(1e-7 * std::pow(1e6, radical_inverse(2, std::uint32_t(k) + 1)));
  std::vector<float> descending = values, ascending = values;
  std::sort(descending.begin(), descending.end(), std::greater<>());
  std::sort(ascending.begin(), ascending.end());
  double exact = 0.0;
  for (float v : values) exact += v;

  // R: spread order; G: largest first (the raster's depth-0 VPLs come first); B: smallest first.
  target.bind();
  api.Disable(GL_DEPTH_TEST);
  api.Enable(GL_BLEND);
  api.BlendEquation(GL_FUNC_ADD);
  api.BlendFunc(GL_ONE, GL_ONE);
  api.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  api.Clear(GL_COLOR_BUFFER_BIT);
  program.use();
  api.BindVertexArray(vao.get());
  for (int k = 0; k < passes; ++k) {
    api.Uniform4f(u_value, values[k], descending[k], ascending[k], 0.0f);
    api.DrawArrays(GL_TRIANGLES, 0, 3);
  }
  context->check("accumulation passes");
  const Image image = target.read();
  context->check("accumulation readback");

  // The same sums in float on the CPU (what IEEE addition in the blender should give).
  float cpu[3] = {0.0f, 0.0f, 0.0f};
  for (int k = 0; k < passes; ++k) {
    cpu[0] += values[k];
    cpu[1] += descending[k];
    cpu[2] += ascending[k];
  }
  double worst[3] = {0.0, 0.0, 0.0};
  for (const glm::vec4& p : image.pixels())
    for (int c = 0; c < 3; ++c) worst[c] = std::max(worst[c], std::abs(p[c] / exact - 1.0));
  const glm::vec4 p0 = image.at(0, 0);
  std::printf("1e5 passes, double sum %.9g: GL %.9g %.9g %.9g (CPU float %.9g %.9g %.9g)\n", exact,
              p0.r, p0.g, p0.b, cpu[0], cpu[1], cpu[2]);
  std::printf("relative error: spread %.3g, largest first %.3g, smallest first %.3g\n", worst[0],
              worst[1], worst[2]);
  // The blender adds in IEEE float: measured bit-identical to the CPU's float sums.
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(p0[c] / cpu[c], 1.0, 1e-6) << c;
  // Measured against the double sum: 1.11e-4 (spread order), 2.10e-4 (largest first, like the
  // raster, whose depth-0 VPLs come first), 1.03e-6 (smallest first). Each value below half an
  // ulp of the running sum (~3e-5 here) is lost: the float sum is biased low. Bounds 1.5x.
  EXPECT_LT(worst[0], 1.7e-4);
  EXPECT_LT(worst[1], 3.2e-4);
  EXPECT_LT(worst[2], 1.6e-6);
}

} // namespace
} // namespace irad
