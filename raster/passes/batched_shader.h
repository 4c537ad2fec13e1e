#pragma once
// The shading passes of a batch of VPLs by instanced draw calls: instance i adds w * C(x) of the
// batch's VPL first + i (core/vpl.h, the same maths as raster/passes/vpl_shader.h) with its shadow cube
// looked up in a ShadowAtlas. The VPLs of one draw share a view-projection and a viewport: with
// interleaved sampling the batch is drawn set by set, each set into its tile, exactly as the
// per-VPL passes of that set (and with the same vertex maths as the depth pre-pass, so GL_LEQUAL
// finds exactly the visible surface).
#include "core/scene.h"
#include "core/vpl.h"
#include "raster/scene/gpu_scene.h"
#include "raster/scene/material_glsl.h"
#include "raster/context/shader_program.h"
#include "raster/shadow/shadow_atlas.h"

#include <glm/glm.hpp>
#include <vector>

namespace irad::gl {

class BatchedShader {
public:
  // Up to `batch` VPLs per upload.
  BatchedShader(const GladGLContext& api, const Scene& scene, float clamp, int batch);

  // Whether this GL's uniform blocks hold a batch of `batch` VPLs.
  static bool fits(const GladGLContext& api, int batch);

  // The batch's VPLs vpls[0..n) with their cube frames and atlas blocks (ShadowAtlas::render).
  void upload(const Vpl* const* vpls, int n, const std::vector<glm::mat3>& frames,
              const std::vector<float>& fars, const std::vector<glm::ivec4>& blocks);
  // Adds the uploaded VPLs first..first + count - 1 through view_projection into the bound
  // framebuffer and viewport (apply_albedo false: irradiance / pi without rho(x), as
  // VplShader).
  void draw(int first, int count, const glm::mat4& view_projection, const ShadowAtlas& shadow,
            bool apply_albedo, const GpuScene& gpu) const;

private:
  const GladGLContext* api_;
  float diagonal_, clamp_;
  int batch_;
  ShaderProgram program_;
  MaterialUniforms material_;
  GLint view_projection_, first_, shadow_res_, shadow_half_, bias_texel_, apply_albedo_;
  Buffer vpl_block_;
  std::vector<float> vpl_data_;
};

} // namespace irad::gl
