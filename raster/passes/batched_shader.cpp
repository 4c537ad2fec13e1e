#include "raster/passes/batched_shader.h"

#include "core/error.h"
#include "raster/glsl/batched_shaders.h"
#include "raster/passes/vpl_shader.h"

#include <cstdint>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>

namespace irad::gl {

namespace {

constexpr GLuint kVplBlockBinding = 1;
constexpr std::size_t kFloatsPerVpl = shaders::kShadingBytesPerVpl / sizeof(float);

// The BatchVpl record of raster/glsl/batched_shaders.h (std140, 144 bytes).
void write_vpl(float* out, const Vpl& vpl, const glm::mat3& frame, float far,
               const glm::ivec4& blocks, float dmin) {
  std::memset(out, 0, kFloatsPerVpl * sizeof(float));
  std::memcpy(out + 0, &vpl.position[0], 3 * sizeof(float));
  std::memcpy(out + 4, &vpl.normal[0], 3 * sizeof(float));
  std::memcpy(out + 8, &vpl.intensity[0], 3 * sizeof(float));
  out[12] = vpl.cos_inner;
  out[13] = vpl.cos_outer;
  out[14] = dmin * dmin;
  out[15] = far;
  const std::int32_t ints[8] = {
      static_cast<std::int32_t>(vpl.kind), 0, 0, 0, blocks.x, blocks.y, blocks.z, blocks.w};
  std::memcpy(out + 16, ints, sizeof(ints));
  for (int c = 0; c < 3; ++c) std::memcpy(out + 24 + 4 * c, &frame[c][0], 3 * sizeof(float));
}

} // namespace

bool BatchedShader::fits(const GladGLContext& api, int batch) {
  GLint block = 0;
  api.GetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &block);
  return batch * shaders::kShadingBytesPerVpl <= block;
}

BatchedShader::BatchedShader(const GladGLContext& api, const Scene& scene, float clamp, int batch)
    : api_(&api), diagonal_(scene.bounds.diagonal()), clamp_(clamp), batch_(batch),
      program_(api, "batched vpl",
               material_source(shaders::batched_source(shaders::batched_vpl_vertex, batch),
                               MaterialFeatures::of(scene)),
               material_source(shaders::batched_source(shaders::batched_vpl_fragment, batch),
                               MaterialFeatures::of(scene))),
      material_(program_), view_projection_(program_.uniform("u_view_projection")),
      first_(program_.uniform("u_first")), shadow_res_(program_.uniform("u_shadow_res")),
      shadow_half_(program_.uniform("u_shadow_half")),
      bias_texel_(program_.uniform("u_bias_texel")),
      apply_albedo_(program_.uniform("u_apply_albedo")), vpl_block_(make_buffer(api)),
      vpl_data_(static_cast<std::size_t>(batch) * kFloatsPerVpl, 0.0f) {
  const GLuint index = api.GetUniformBlockIndex(program_.get(), "VplBatch");
  if (index == GL_INVALID_INDEX) throw Error("", "shader batched vpl", "no block VplBatch");
  api.UniformBlockBinding(program_.get(), index, kVplBlockBinding);
  program_.use();
  api.Uniform1i(program_.uniform("u_shadow_atlas"), shadow_unit);
  // Scale-relative constants, as VplShader: the coincidence guard and the shadow bias.
  api.Uniform1f(program_.uniform("u_min_dist2"), 1e-10f * diagonal_ * diagonal_);
  api.Uniform1f(program_.uniform("u_bias_constant"), 2e-4f * diagonal_);
}

void BatchedShader::upload(const Vpl* const* vpls, int n, const std::vector<glm::mat3>& frames,
                           const std::vector<float>& fars, const std::vector<glm::ivec4>& blocks) {
  if (n > batch_) throw Error("", "batched vpl", "more VPLs than the batch holds");
  for (int s = 0; s < n; ++s) {
    const auto u = static_cast<std::size_t>(s);
    const float dmin = vpls[s]->clamped() ? clamp_ * diagonal_ : 0.0f;
    write_vpl(vpl_data_.data() + kFloatsPerVpl * u, *vpls[s], frames[u], fars[u], blocks[u], dmin);
  }
  // A new store per batch (no wait for the draws that read the last one).
  api_->BindBuffer(GL_UNIFORM_BUFFER, vpl_block_.get());
  api_->BufferData(GL_UNIFORM_BUFFER, static_cast<GLsizeiptr>(vpl_data_.size() * sizeof(float)),
                   vpl_data_.data(), GL_STREAM_DRAW);
}

void BatchedShader::draw(int first, int count, const glm::mat4& view_projection,
                         const ShadowAtlas& shadow, bool apply_albedo, const GpuScene& gpu) const {
  const GladGLContext& api = *api_;
  api.BindBufferBase(GL_UNIFORM_BUFFER, kVplBlockBinding, vpl_block_.get());
  set_additive_state(api);
  program_.use();
  api.UniformMatrix4fv(view_projection_, 1, GL_FALSE, glm::value_ptr(view_projection));
  api.Uniform1i(first_, first);
  api.Uniform1i(shadow_res_, shadow.resolution());
  api.Uniform1i(shadow_half_, shadow.resolution() / 2 + 1);
  api.Uniform1f(bias_texel_, shadow.texel_angle());
  api.Uniform1i(apply_albedo_, apply_albedo ? 1 : 0);
  api.ActiveTexture(GL_TEXTURE0 + shadow_unit);
  api.BindTexture(GL_TEXTURE_2D, shadow.texture());
  if (!apply_albedo) {
    gpu.draw_covered(count, [&](const Material& m) { material_.bind_alpha(api, gpu, m); });
    return;
  }
  gpu.draw_instanced(count, [&](const Material& m) {
    const glm::vec3 rho = m.specular ? glm::vec3(0.0f) : m.base_color; // mirrors: no diffuse
    material_.bind_base(api, gpu, m, rho);
  });
}

} // namespace irad::gl
