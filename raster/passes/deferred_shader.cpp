#include "raster/passes/deferred_shader.h"

#include "core/scene/mirrors.h"
#include "core/util/error.h"
#include "raster/glsl/batched_shaders.h"
#include "raster/glsl/brdf_glsl.h"
#include "raster/glsl/cube_glsl.h"
#include "raster/glsl/deferred_shaders.h"
#include "raster/glsl/mirror_shaders.h"
#include "raster/glsl/shaders.h"
#include "raster/passes/vpl_shader.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>
#include <string>

namespace irad::gl {

namespace {

constexpr GLuint kVplBlockBinding = 1;
constexpr std::size_t floats_per_vpl(bool glossy) {
  return static_cast<std::size_t>(shaders::shading_bytes_per_vpl(glossy)) / sizeof(float);
}
constexpr std::size_t kFloatsPerVpl = floats_per_vpl(false);
// The G-buffer's position, normal and albedo at gbuffer_unit, + 1, + 2 (after the shadow atlas
// at shadow_unit).
constexpr GLint gbuffer_unit = 3;
constexpr GLint ortho_unit = 6;
constexpr GLint gradient_unit = 7;    // ShadowLookup::gradient
constexpr GLint mirror_unit = 8;      // the mirror polygons' corners
constexpr GLint list_unit = 9;        // TilePixels::list
constexpr GLint brdf_unit = 10;       // glossy: the G-buffer's (base, f90) and (f0, metallic)
constexpr GLint table_unit = 12;      // glossy: the albedo table (the VSLs' widened lobes)
constexpr GLint visibility_unit = 13; // rays: ShadowLookup::visibility

// The BatchVpl record of raster/glsl/deferred_shaders.h (std140, 160 bytes). `triangles`: the
// triangles of the VPL's mirror polygon (0: its light reaches nothing, as VplShader's).
void write_vpl(float* out, const AtlasVpl& a, float dmin2, int triangles) {
  const Vpl& vpl = *a.vpl;
  std::memset(out, 0, kFloatsPerVpl * sizeof(float));
  std::memcpy(out + 0, &vpl.position[0], 3 * sizeof(float));
  std::memcpy(out + 4, &vpl.normal[0], 3 * sizeof(float));
  std::memcpy(out + 8, &vpl.intensity[0], 3 * sizeof(float));
  const bool directional = vpl.kind == VplKind::Directional;
  out[12] = directional ? a.texel : vpl.cos_inner;
  out[13] = directional ? a.half_width : vpl.cos_outer;
  out[14] = dmin2;
  out[15] = a.far;
  const std::int32_t ints[8] = {static_cast<std::int32_t>(vpl.kind),
                                vpl.mirror,
                                triangles,
                                vpl.ray_reachable() ? 1 : 0,
                                a.blocks.x,
                                a.blocks.y,
                                a.blocks.z,
                                a.blocks.w};
  std::memcpy(out + 16, ints, sizeof(ints));
  for (int c = 0; c < 3; ++c) {
    if (directional) { // row c of the affine lookup
      for (int k = 0; k < 4; ++k) out[24 + 4 * c + k] = a.lookup[k][c];
    } else {
      std::memcpy(out + 24 + 4 * c, &a.frame[c][0], 3 * sizeof(float));
    }
  }
  if (vpl.mirror >= 0) std::memcpy(out + 36, &vpl.mirror_plane[0], 4 * sizeof(float));
}

// The lobe[4] of a glossy scene's BatchVpl record, after write_vpl's (zero for a Lambertian VPL).
void write_lobe(float* out, const AtlasVpl& a) {
  const std::array<float, 16> r = lobe_record(*a.vpl, a.lobe);
  std::memcpy(out, r.data(), sizeof(float) * r.size());
}

std::string defines(bool mirrors, bool glossy, bool receivers, bool lobes, bool rays) {
  return std::string(mirrors ? "#define IRAD_MIRRORS 1\n" : "") +
         (rays ? "#define IRAD_RAYS 1\n" : "") + (glossy ? "#define IRAD_GLOSSY 1\n" : "") +
         (receivers ? "#define IRAD_GLOSSY_RECEIVERS 1\n" : "") +
         (lobes ? "#define IRAD_GLOSSY_VPLS 1\n" : "");
}

// The fragment shader for `batch` VPLs, with the occluder planes' fetches or without them, the
// unsure light or without it, the mirrored VPLs' pyramid test or without it, the glTF BRDF or
// without it, the glossy VPLs' lobes or without them.
std::string fragment_source(int batch, bool planes, bool unsure, const std::string& defined) {
  std::string source = shaders::with_brdf(shaders::with_cube_lookup(
      shaders::batched_source(shaders::deferred_vpl_fragment, batch, defined)));
  insert_glsl(source, "#pragma irad_planes\n",
              planes ? "const bool u_planes = true;\n" : "const bool u_planes = false;\n");
  insert_glsl(source, "#pragma irad_unsure\n",
              unsure ? "const bool u_unsure = true;\n" : "const bool u_unsure = false;\n");
  insert_glsl(source, "#pragma irad_luminance\n", shaders::luminance_glsl);
  insert_glsl(source, "#pragma irad_mirror_pyramid\n", shaders::mirror_pyramid_glsl);
  return source;
}

// The corners of every mirror polygon: row p holds polygon p's, three texels per triangle.
Texture corner_texture(const GladGLContext& api, const std::vector<MirrorPolygon>& mirrors) {
  GLint side = 0;
  api.GetIntegerv(GL_MAX_TEXTURE_SIZE, &side);
  if (static_cast<GLint>(mirrors.size()) > side)
    throw Error("", "mirrors",
                std::to_string(mirrors.size()) + " mirror polygons do not fit this OpenGL");
  constexpr int width = 3 * static_cast<int>(MirrorPolygon::max_triangles);
  std::vector<float> texels(mirrors.size() * width * 3, 0.0f);
  for (std::size_t p = 0; p < mirrors.size(); ++p) {
    const std::size_t corners = std::min(mirrors[p].triangles.size(), std::size_t(width));
    std::memcpy(&texels[p * width * 3], &mirrors[p].triangles[0][0], corners * 3 * sizeof(float));
  }
  Texture t = make_float_texture(api, width, static_cast<int>(mirrors.size()), GL_RGB32F, GL_RGB);
  api.BindTexture(GL_TEXTURE_2D, t.get());
  api.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  api.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, static_cast<GLsizei>(mirrors.size()), GL_RGB,
                    GL_FLOAT, texels.data());
  api.BindTexture(GL_TEXTURE_2D, 0);
  return t;
}

} // namespace

int DeferredShader::capacity(const GladGLContext& api, int wanted, bool glossy) {
  GLint block = 0;
  api.GetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &block);
  return std::min(wanted, static_cast<int>(block) / shaders::shading_bytes_per_vpl(glossy));
}

DeferredShader::Program::Program(const GladGLContext& api, int batch, bool planes, bool unsure,
                                 bool mirrors, bool glossy, bool receivers, bool lobes, bool rays)
    : program(
          api, "deferred vpl",
          shaders::batched_source(shaders::deferred_vpl_vertex, batch,
                                  defines(mirrors, glossy, receivers, lobes, rays)),
          fragment_source(batch, planes, unsure, defines(mirrors, glossy, receivers, lobes, rays))),
      first(program.uniform("u_first")), tile_origin(program.uniform("u_tile_origin")),
      pixel(program.uniform("u_pixel")), size(program.uniform("u_size")),
      // (optional: the rays' programs read no shadow map)
      shadow_res(program.optional_uniform("u_shadow_res")),
      shadow_half(program.optional_uniform("u_shadow_half")),
      bias_texel(program.optional_uniform("u_bias_texel")),
      ortho_res(program.optional_uniform("u_ortho_res")),
      apply_albedo(program.uniform("u_apply_albedo")), listed(program.uniform("u_listed")),
      eye(program.optional_uniform("u_eye")),
      traced(program.optional_uniform("u_traced_roughness")), depth(program.uniform("u_depth")) {
  const GLuint index = api.GetUniformBlockIndex(program.get(), "VplBatch");
  if (index == GL_INVALID_INDEX) throw Error("", "shader deferred vpl", "no block VplBatch");
  api.UniformBlockBinding(program.get(), index, kVplBlockBinding);
  program.use();
  program.set_sampler("u_shadow_atlas", shadow_unit);
  program.set_sampler("u_ortho_atlas", ortho_unit);
  program.set_sampler("u_shadow_gradient", gradient_unit);
  program.set_sampler("u_position", gbuffer_unit);
  program.set_sampler("u_normal", gbuffer_unit + 1);
  program.set_sampler("u_albedo", gbuffer_unit + 2);
  program.set_sampler("u_pixel_list", list_unit);
  program.set_sampler("u_base", brdf_unit);
  program.set_sampler("u_specular", brdf_unit + 1);
  program.set_sampler("u_albedo_table", table_unit);
  program.set_sampler("u_mirror_corners", mirror_unit);
  if (rays) program.set_sampler("u_visibility", visibility_unit);
}

DeferredShader::DeferredShader(const GladGLContext& api, const Scene& scene, float clamp, int batch,
                               bool planes, bool unsure, const std::vector<MirrorPolygon>& mirrors)
    : api_(&api), diagonal_(scene.bounds.diagonal()), clamp_(clamp), batch_(batch), planes_(planes),
      glossy_(!scene.all_lambertian()), unsure_(unsure), mirrors_(!mirrors.empty()),
      vpl_block_(make_buffer(api)), empty_vao_(make_vertex_array(api)),
      vpl_data_(static_cast<std::size_t>(batch) * floats_per_vpl(glossy_), 0.0f) {
  if (!mirrors.empty()) {
    mirror_corners_ = corner_texture(api, mirrors);
    for (const MirrorPolygon& m : mirrors)
      mirror_triangles_.push_back(
          static_cast<int>(std::min(m.triangles.size() / 3, MirrorPolygon::max_triangles)));
  }
  if (glossy_) albedo_table_ = albedo_table_texture(api);
  program(glossy_, glossy_, false); // the one every draw can take: compile errors show here
}

void DeferredShader::set_planes(bool planes) {
  if (planes == planes_) return;
  planes_ = planes;
  for (std::size_t k = 0; k < 4; ++k) programs_[k].reset(); // the rays' programs read no map
}

const DeferredShader::Program& DeferredShader::program(bool receivers, bool lobes,
                                                       bool rays) const {
  std::unique_ptr<Program>& p = programs_[(receivers ? 1 : 0) + (lobes ? 2 : 0) + (rays ? 4 : 0)];
  if (p) return *p;
  p = std::make_unique<Program>(*api_, batch_, planes_ && !rays, unsure_ && !rays, mirrors_,
                                glossy_, receivers, lobes, rays);
  // Scale-relative constants, as VplShader: the coincidence guard and the shadow bias.
  const GladGLContext& api = *api_;
  api.Uniform1f(p->program.uniform("u_min_dist2"), 1e-10f * diagonal_ * diagonal_);
  if (!rays) { // the shadow lookups' (the rays' programs have none)
    api.Uniform1f(p->program.uniform("u_bias_constant"), 2e-4f * diagonal_);
    api.Uniform1f(p->program.uniform("u_offset_texels"), normal_offset_texels(planes_));
  }
  return *p;
}

void DeferredShader::upload(const AtlasVpl* vpls, int n) {
  if (n > batch_) throw Error("", "deferred vpl", "more VPLs than the batch holds");
  lobed_.assign(static_cast<std::size_t>(n), false);
  for (int s = 0; s < n; ++s) {
    const Vpl& vpl = *vpls[s].vpl;
    const float dmin2 = clamp_distance2(vpl, clamp_ * diagonal_);
    const auto mirror = static_cast<std::size_t>(vpl.mirror);
    const int triangles =
        vpl.mirror >= 0 && mirror < mirror_triangles_.size() ? mirror_triangles_[mirror] : 0;
    float* out = vpl_data_.data() + floats_per_vpl(glossy_) * static_cast<std::size_t>(s);
    write_vpl(out, vpls[s], dmin2, triangles);
    if (glossy_) write_lobe(out + kFloatsPerVpl, vpls[s]);
    lobed_[static_cast<std::size_t>(s)] = vpls[s].lobe != nullptr;
  }
  // A new store per batch (no wait for the draws that read the last one).
  api_->BindBuffer(GL_UNIFORM_BUFFER, vpl_block_.get());
  api_->BufferData(GL_UNIFORM_BUFFER, static_cast<GLsizeiptr>(vpl_data_.size() * sizeof(float)),
                   vpl_data_.data(), GL_STREAM_DRAW);
}

void DeferredShader::draw(int first, int count, const TilePixels& pixels, const GBuffer& gbuffer,
                          const ShadowLookup& shadow, bool apply_albedo) const {
  if (first < 0 || first + count > static_cast<int>(lobed_.size()))
    throw Error("", "deferred vpl", "a draw beyond the uploaded VPLs");
  const auto lobed = [&](int i) { return lobed_[static_cast<std::size_t>(i)]; };
  for (int end = first + count; first < end;) {
    int run = first + 1;
    while (run < end && lobed(run) == lobed(first)) ++run;
    const bool lobes = glossy_ && lobed(first), rays = shadow.visibility != 0;
    if (masked(pixels)) {
      draw_run(program(false, lobes, rays), first, run - first, pixels, gbuffer, shadow,
               apply_albedo, shaders::kLambertianReceiverDepth);
      draw_run(program(true, lobes, rays), first, run - first, pixels, gbuffer, shadow,
               apply_albedo, shaders::kGlossyReceiverDepth);
    } else {
      draw_run(program(glossy_, lobes, rays), first, run - first, pixels, gbuffer, shadow,
               apply_albedo, shaders::kLambertianReceiverDepth);
    }
    first = run;
  }
}

void DeferredShader::draw_run(const Program& p, int first, int count, const TilePixels& pixels,
                              const GBuffer& gbuffer, const ShadowLookup& shadow, bool apply_albedo,
                              float depth) const {
  const GladGLContext& api = *api_;
  api.BindBufferBase(GL_UNIFORM_BUFFER, kVplBlockBinding, vpl_block_.get());
  if (masked(pixels)) {
    api.Enable(GL_DEPTH_TEST);
    api.DepthFunc(GL_EQUAL);
  } else {
    api.Disable(GL_DEPTH_TEST);
  }
  api.DepthMask(GL_FALSE);
  api.Enable(GL_BLEND);
  api.BlendEquation(GL_FUNC_ADD);
  api.BlendFunc(GL_ONE, GL_ONE);
  p.program.use();
  api.Uniform1i(p.first, first);
  api.Uniform1f(p.depth, depth);
  api.Uniform2i(p.tile_origin, pixels.origin.x, pixels.origin.y);
  api.Uniform3i(p.pixel, pixels.k, pixels.offset.x, pixels.offset.y);
  api.Uniform2i(p.size, gbuffer.width(), gbuffer.height());
  api.Uniform1i(p.shadow_res, shadow.resolution);
  api.Uniform1i(p.shadow_half, shadow.resolution / 2 + 1);
  // Angular size of one texel at the centre of a face, as ShadowCube::texel_angle.
  api.Uniform1f(p.bias_texel, 2.0f / static_cast<float>(shadow.resolution));
  api.Uniform1i(p.apply_albedo, apply_albedo ? 1 : 0);
  api.Uniform1i(p.listed, pixels.list != 0 ? 1 : 0);
  if (pixels.list != 0) {
    api.ActiveTexture(GL_TEXTURE0 + list_unit);
    api.BindTexture(GL_TEXTURE_2D, pixels.list);
  }
  api.Uniform1i(p.ortho_res, shadow.ortho_resolution);
  api.ActiveTexture(GL_TEXTURE0 + shadow_unit);
  api.BindTexture(GL_TEXTURE_2D, shadow.texture);
  api.ActiveTexture(GL_TEXTURE0 + ortho_unit);
  api.BindTexture(GL_TEXTURE_2D, shadow.ortho_texture);
  if (planes_ && shadow.visibility == 0) {
    if (shadow.gradient == 0) throw Error("", "deferred vpl", "shadow lookup without gradients");
    api.ActiveTexture(GL_TEXTURE0 + gradient_unit);
    api.BindTexture(GL_TEXTURE_2D, shadow.gradient);
  }
  if (shadow.visibility != 0) {
    api.ActiveTexture(GL_TEXTURE0 + visibility_unit);
    api.BindTexture(GL_TEXTURE_2D_ARRAY, shadow.visibility);
  }
  if (mirror_corners_) {
    api.ActiveTexture(GL_TEXTURE0 + mirror_unit);
    api.BindTexture(GL_TEXTURE_2D, mirror_corners_.get());
  }
  gbuffer.bind_textures(gbuffer_unit);
  if (glossy_) {
    if (!gbuffer.glossy())
      throw Error("", "deferred vpl", "a glossy scene's G-buffer lacks the BRDF");
    gbuffer.bind_brdf_textures(brdf_unit);
    api.ActiveTexture(GL_TEXTURE0 + table_unit);
    api.BindTexture(GL_TEXTURE_2D, albedo_table_.get());
    api.Uniform4fv(p.eye, 1, glm::value_ptr(gbuffer.eye()));
    api.Uniform1f(p.traced, traced_roughness_);
  }
  api.BindVertexArray(empty_vao_.get());
  api.DrawArraysInstanced(GL_TRIANGLES, 0, 3, count);
}

} // namespace irad::gl
