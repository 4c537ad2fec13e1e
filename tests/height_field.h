#pragma once
// A height field for the camera's tests (tests/test_camera_lod.cpp, tests/test_index_chunks.cpp),
// and its G-buffer read back.
#include "core/camera/view.h"
#include "core/scene/scene.h"
#include "core/scene/scene_builder.h"
#include "raster/image/gbuffer.h"
#include "raster/passes/camera_lod.h"
#include "raster/passes/camera_passes.h"
#include "raster/scene/gpu_scene.h"

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace irad::test_support {

// A height field over [-1, 1]^2 (y up) of q x q quads, a few octaves of bumps as
// scripts/make_large_glb.py makes its terrain, with its analytic normals, material `material`.
inline void add_terrain(Scene& s, int q, std::uint32_t material) {
  const auto first = static_cast<std::uint32_t>(s.positions.size());
  const float octaves[3][3] = {{2.1f, 1.7f, 0.12f}, {5.3f, 6.1f, 0.04f}, {41.0f, 37.0f, 0.01f}};
  for (int r = 0; r <= q; ++r)
    for (int c = 0; c <= q; ++c) {
      const float x = 2.0f * float(c) / float(q) - 1.0f, z = 2.0f * float(r) / float(q) - 1.0f;
      float y = 0.0f, dx = 0.0f, dz = 0.0f;
      for (const auto& o : octaves) {
        y += o[2] * std::sin(o[0] * x) * std::cos(o[1] * z);
        dx += o[2] * o[0] * std::cos(o[0] * x) * std::cos(o[1] * z);
        dz -= o[2] * o[1] * std::sin(o[0] * x) * std::sin(o[1] * z);
      }
      s.positions.emplace_back(x, y, z);
      s.normals.push_back(glm::normalize(glm::vec3(-dx, 1.0f, -dz)));
    }
  const auto n = static_cast<std::uint32_t>(q + 1);
  for (std::uint32_t r = 0; r < std::uint32_t(q); ++r)
    for (std::uint32_t c = 0; c < std::uint32_t(q); ++c) {
      const std::uint32_t a = first + r * n + c;
      s.triangles.emplace_back(a, a + n, a + 1);
      s.triangles.emplace_back(a + 1, a + n, a + n + 1);
      s.triangle_material.insert(s.triangle_material.end(), 2, material);
    }
}

// The terrain lit by a square light above it.
inline Scene lit_terrain(int q) {
  Scene s;
  add_terrain(s, q, add_material(s, glm::vec3(0.6f)));
  const std::uint32_t light = add_material(s, glm::vec3(0.0f), glm::vec3(20.0f));
  add_quad(s, {-0.2f, 1.5f, -0.2f}, {0.2f, 1.5f, -0.2f}, {0.2f, 1.5f, 0.2f}, {-0.2f, 1.5f, 0.2f},
           light); // facing down
  s.cameras.push_back(look_at({0.0f, 0.8f, 1.6f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 0.7f));
  finish(s);
  return s;
}

struct GBufferPixels {
  std::vector<glm::vec4> position, normal;
};

// The G-buffer of `view` (every triangle, or through `lod` prepared for it), read back.
inline GBufferPixels draw_gbuffer(const GladGLContext& api, const gl::GpuScene& gpu,
                                  const View& view, const gl::CameraLod* lod) {
  const gl::Renderbuffer depth = gl::make_renderbuffer(api);
  api.BindRenderbuffer(GL_RENDERBUFFER, depth.get());
  api.RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, view.width, view.height);
  gl::GBuffer gbuffer(api, view.width, view.height, depth.get(), false);
  const gl::CameraPasses camera(api, gpu.features());
  camera.gbuffer(gbuffer, view.projection * view.view, gl::eye_uniform(view), gpu, lod);
  GBufferPixels out;
  const auto n = static_cast<std::size_t>(view.width) * static_cast<std::size_t>(view.height);
  for (int k = 0; k < 2; ++k) {
    std::vector<glm::vec4>& into = k == 0 ? out.position : out.normal;
    into.resize(n);
    api.ReadBuffer(static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + k));
    api.ReadPixels(0, 0, view.width, view.height, GL_RGBA, GL_FLOAT, into.data());
  }
  return out;
}

} // namespace irad::test_support
