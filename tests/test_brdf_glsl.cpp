// The raster's GLSL BRDF (raster/glsl/brdf_glsl.h) against core's C++ one (core/material/brdf.h):
// a fragment program evaluates f_r for random materials and direction pairs read from a float
// texture, one pair per pixel, and the read-back values must equal Brdf::eval's.
#include "core/material/albedo_table.h"
#include "core/material/brdf.h"
#include "raster/context/gl_context.h"
#include "raster/context/shader_program.h"
#include "raster/glsl/brdf_glsl.h"
#include "raster/image/target.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <random>
#include <string>
#include <vector>

namespace irad {
namespace IRAD_UNITY_ID {

constexpr int kWidth = 64, kHeight = 32; // one case per pixel (kFragment names kWidth's 64)
constexpr int kTexels = 5;               // per case

const char* const kVertex = R"(#version 330 core
void main() {
  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  gl_Position = vec4(p, 0.0, 1.0);
}
)";

// Case i's texels: (base, metallic), (f0, roughness), (n, f90), (wo, 0), (wi, 0); f_r(wo, wi), or
// with u_mode 1 the directional albedo a(wo) from the uploaded AlbedoTable, with 2 the diffuse
// lobe alone.
const char* const kFragment = R"(#version 330 core
#pragma irad_brdf
#pragma irad_brdf_albedo
uniform sampler2D u_cases;
uniform int u_mode;
out vec4 colour;
void main() {
  int i = int(gl_FragCoord.y) * 64 + int(gl_FragCoord.x); // 64: kWidth
  vec4 a = texelFetch(u_cases, ivec2(5 * i + 0, 0), 0);
  vec4 b = texelFetch(u_cases, ivec2(5 * i + 1, 0), 0);
  vec4 c = texelFetch(u_cases, ivec2(5 * i + 2, 0), 0);
  vec3 wo = texelFetch(u_cases, ivec2(5 * i + 3, 0), 0).xyz;
  vec3 wi = texelFetch(u_cases, ivec2(5 * i + 4, 0), 0).xyz;
  if (u_mode == 1)
    colour = vec4(brdf_albedo(a.rgb, a.a, b.a, b.rgb, c.a, dot(c.xyz, wo)), 1.0);
  else if (u_mode == 2)
    colour = vec4(brdf_eval_diffuse(a.rgb, a.a, b.a, b.rgb, c.a, c.xyz, wo, wi), 1.0);
  else
    colour = vec4(brdf_eval(a.rgb, a.a, b.a, b.rgb, c.a, c.xyz, wo, wi), 1.0);
}
)";

struct Case {
  BrdfInputs in;
  glm::vec3 n, wo, wi;
};

glm::vec3 unit(std::mt19937& rng) {
  std::normal_distribution<float> g;
  return glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
}

// Random materials (a quarter Lambertian) and directions, most above the surface.
std::vector<Case> random_cases(int count) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Case> cases;
  for (int k = 0; k < count; ++k) {
    Case c;
    c.in.base = {u(rng), u(rng), u(rng)};
    if (k % 4 != 0) {
      c.in.metallic = k % 3 == 0 ? 1.0f : u(rng);
      c.in.roughness = 0.05f + 0.95f * u(rng);
      c.in.f90 = u(rng);
      c.in.f0 = glm::vec3(0.04f) * c.in.f90;
    }
    c.n = unit(rng);
    c.wo = unit(rng);
    c.wi = unit(rng);
    if (glm::dot(c.wo, c.n) < 0.0f && k % 8 != 0) c.wo = -c.wo; // some stay below
    if (glm::dot(c.wi, c.n) < 0.0f && k % 8 != 1) c.wi = -c.wi;
    cases.push_back(c);
  }
  return cases;
}

std::vector<float> case_texels(const std::vector<Case>& cases) {
  std::vector<float> t;
  for (const Case& c : cases) {
    for (const glm::vec4& v :
         {glm::vec4(c.in.base, c.in.metallic), glm::vec4(c.in.f0, c.in.roughness),
          glm::vec4(c.n, c.in.f90), glm::vec4(c.wo, 0.0f), glm::vec4(c.wi, 0.0f)})
      t.insert(t.end(), {v.x, v.y, v.z, v.w});
  }
  return t;
}

// Draws kFragment over one pixel per case, the cases on unit 0 and core's albedo table on unit 1;
// row 0 of the image at the top (case i at GL row i / kWidth).
enum Mode { kEval, kAlbedo, kDiffuse };

Image render_cases(const std::vector<Case>& cases, Mode mode) {
  const auto context = gl::create_osmesa_context();
  const GladGLContext& api = context->api();
  const gl::ShaderProgram program(api, "brdf test", kVertex, gl::shaders::with_brdf(kFragment));
  const int texels = kWidth * kHeight * kTexels;
  const gl::Texture input = gl::make_float_texture(api, texels, 1);
  const std::vector<float> data = case_texels(cases);
  api.BindTexture(GL_TEXTURE_2D, input.get());
  api.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, texels, 1, GL_RGBA, GL_FLOAT, data.data());
  const gl::Texture table =
      gl::make_float_texture(api, AlbedoTable::kRough, AlbedoTable::kMu, GL_RGB32F, GL_RGB);
  api.BindTexture(GL_TEXTURE_2D, table.get());
  api.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  api.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, AlbedoTable::kRough, AlbedoTable::kMu, GL_RGB, GL_FLOAT,
                    AlbedoTable::get().cells().data());
  gl::Target target(api, kWidth, kHeight);
  target.bind();
  const gl::VertexArray vao = gl::make_vertex_array(api);
  api.BindVertexArray(vao.get());
  program.use();
  api.ActiveTexture(GL_TEXTURE0);
  api.BindTexture(GL_TEXTURE_2D, input.get());
  api.ActiveTexture(GL_TEXTURE1);
  api.BindTexture(GL_TEXTURE_2D, table.get());
  program.set_sampler("u_cases", 0);
  program.set_sampler("u_albedo_table", 1);
  api.Uniform1i(api.GetUniformLocation(program.get(), "u_mode"), mode);
  api.DrawArrays(GL_TRIANGLES, 0, 3);
  context->check("brdf test draw");
  return target.read();
}

// f_r, and its diffuse lobe alone (brdf_eval_diffuse: the receivers whose specular lobe the glossy
// camera pass traces).
TEST(BrdfGlsl, EqualsTheCppBrdfAtSampledDirections) {
  const std::vector<Case> cases = random_cases(kWidth * kHeight);
  for (const Mode mode : {kEval, kDiffuse}) {
    const Image image = render_cases(cases, mode);
    double worst = 0.0;
    int zeros = 0;
    for (int i = 0; i < kWidth * kHeight; ++i) {
      const Case& c = cases[std::size_t(i)];
      const Brdf brdf(c.in, c.n);
      const glm::vec3 cpu = mode == kEval ? brdf.eval(c.wo, c.wi) : brdf.eval_diffuse(c.wo, c.wi);
      const glm::vec3 gpu(image.at(i % kWidth, kHeight - 1 - i / kWidth));
      if (cpu == glm::vec3(0.0f)) {
        ++zeros;
        EXPECT_EQ(gpu, glm::vec3(0.0f)) << "case " << i;
        continue;
      }
      for (int ch = 0; ch < 3; ++ch)
        worst = std::max(worst, std::abs(double(gpu[ch]) - cpu[ch]) / std::max(cpu[ch], 1e-6f));
    }
    std::printf("%s, %d cases (%d zero): worst relative |glsl - c++| %.2e\n",
                mode == kEval ? "f_r" : "diffuse lobe", kWidth * kHeight, zeros, worst);
    // Measured: f_r 2.0e-4, its diffuse lobe 2.0e-7 (llvmpipe; both sides in single precision, in
    // different operation orders).
    EXPECT_LT(worst, 1e-3);
    EXPECT_GT(zeros, 100);
  }
}

// brdf_albedo_glsl against directional_albedo (core/material/brdf.h) at the same cases: the
// interleaved resolve's demodulation and nothing else read it, but it must be the CPU's.
TEST(BrdfGlsl, DirectionalAlbedoEqualsTheCpps) {
  const std::vector<Case> cases = random_cases(kWidth * kHeight);
  const Image image = render_cases(cases, kAlbedo);
  double worst = 0.0;
  for (int i = 0; i < kWidth * kHeight; ++i) {
    const Case& c = cases[std::size_t(i)];
    const glm::vec3 cpu = directional_albedo(c.in, glm::dot(c.n, c.wo));
    const glm::vec3 gpu(image.at(i % kWidth, kHeight - 1 - i / kWidth));
    for (int ch = 0; ch < 3; ++ch)
      worst = std::max(worst, std::abs(double(gpu[ch]) - cpu[ch]) / std::max(cpu[ch], 1e-3f));
  }
  std::printf("%d cases: worst relative |glsl - c++| of the directional albedo %.2e\n",
              kWidth * kHeight, worst);
  // Measured: 3.2e-7 (llvmpipe; the same single-precision sums in another order).
  EXPECT_LT(worst, 1e-5);
}

} // namespace IRAD_UNITY_ID
} // namespace irad
