#include "raster/raster_renderer.h"

#include "core/error.h"
#include "raster/gl_context.h"
#include "raster/gpu_scene.h"
#include "raster/pass_timer.h"
#include "raster/shaders.h"
#include "raster/shadow_cube.h"
#include "raster/target.h"

#include <chrono>
#include <glm/gtc/type_ptr.hpp>
#include <optional>

namespace irad {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

bool carries_light(const Vpl& v) {
  return v.intensity.x > 0.0f || v.intensity.y > 0.0f || v.intensity.z > 0.0f;
}

// Uniform locations of the VPL shading program, looked up once.
struct VplUniforms {
  GLint view_projection, position, normal, intensity, kind, spot_cos, dmin2, min_dist2, shadow,
      frame, bias_constant, bias_texel, base_color, has_base_texture, base_texture;
  explicit VplUniforms(const gl::ShaderProgram& p)
      : view_projection(p.uniform("u_view_projection")), position(p.uniform("u_vpl_position")),
        normal(p.uniform("u_vpl_normal")), intensity(p.uniform("u_vpl_intensity")),
        kind(p.uniform("u_vpl_kind")), spot_cos(p.uniform("u_spot_cos")),
        dmin2(p.uniform("u_dmin2")), min_dist2(p.uniform("u_min_dist2")),
        shadow(p.uniform("u_shadow")), frame(p.uniform("u_shadow_frame")),
        bias_constant(p.uniform("u_bias_constant")), bias_texel(p.uniform("u_bias_texel")),
        base_color(p.uniform("u_base_color")), has_base_texture(p.uniform("u_has_base_texture")),
        base_texture(p.uniform("u_base_texture")) {}
};

struct EmissionUniforms {
  GLint view_projection, emission, has_texture, texture, double_sided;
  explicit EmissionUniforms(const gl::ShaderProgram& p)
      : view_projection(p.uniform("u_view_projection")), emission(p.uniform("u_emission")),
        has_texture(p.uniform("u_has_emissive_texture")), texture(p.uniform("u_emissive_texture")),
        double_sided(p.uniform("u_double_sided")) {}
};

constexpr GLint shadow_unit = 0;
constexpr GLint material_unit = 1;

} // namespace

struct RasterRenderer::Impl {
  const Scene& scene;
  RasterOptions options;
  std::unique_ptr<gl::Context> context;
  const GladGLContext& api;
  gl::GpuScene gpu;
  gl::ShadowCube shadow;
  gl::ShaderProgram depth_program;
  gl::ShaderProgram emission_program;
  gl::ShaderProgram vpl_program;
  GLint depth_view_projection;
  EmissionUniforms emission_uniforms;
  VplUniforms vpl_uniforms;
  std::unique_ptr<gl::Target> target;

  Impl(const Scene& s, const RasterOptions& o, std::unique_ptr<gl::Context> c)
      : scene(s), options(o), context(std::move(c)), api(context->api()), gpu(api, s),
        shadow(api, o.shadow_resolution, s.bounds),
        depth_program(api, "depth", gl::shaders::camera_vertex, gl::shaders::depth_fragment),
        emission_program(api, "emission", gl::shaders::camera_vertex,
                         gl::shaders::emission_fragment),
        vpl_program(api, "vpl", gl::shaders::camera_vertex, gl::shaders::vpl_fragment),
        depth_view_projection(depth_program.uniform("u_view_projection")),
        emission_uniforms(emission_program), vpl_uniforms(vpl_program) {
    // Samplers of different types may not share a unit: fix every sampler's unit once.
    emission_program.use();
    api.Uniform1i(emission_uniforms.texture, material_unit);
    vpl_program.use();
    api.Uniform1i(vpl_uniforms.shadow, shadow_unit);
    api.Uniform1i(vpl_uniforms.base_texture, material_unit);
    context->check("raster set-up");
  }

  void depth_prepass(const glm::mat4& vp);
  void emitters(const glm::mat4& vp);
  void shade(const Vpl& vpl, const glm::mat3& frame, const glm::mat4& vp);
  void bind_material_texture(int texture, GLint has_uniform);
};

void RasterRenderer::Impl::depth_prepass(const glm::mat4& vp) {
  target->bind();
  api.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  api.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  api.ClearDepth(1.0);
  api.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  api.Enable(GL_DEPTH_TEST);
  api.DepthFunc(GL_LESS);
  api.DepthMask(GL_TRUE);
  api.Disable(GL_BLEND);
  api.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  depth_program.use();
  api.UniformMatrix4fv(depth_view_projection, 1, GL_FALSE, glm::value_ptr(vp));
  gpu.draw_all();
  api.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

void RasterRenderer::Impl::bind_material_texture(int texture, GLint has_uniform) {
  api.Uniform1i(has_uniform, texture >= 0 ? 1 : 0);
  if (texture < 0) return;
  api.ActiveTexture(GL_TEXTURE0 + material_unit);
  api.BindTexture(GL_TEXTURE_2D, gpu.texture(texture));
}

// Additive passes over the pre-pass depth: exactly the visible surface passes GL_LEQUAL.
void set_additive_state(const GladGLContext& api) {
  api.Enable(GL_DEPTH_TEST);
  api.DepthFunc(GL_LEQUAL);
  api.DepthMask(GL_FALSE);
  api.Enable(GL_BLEND);
  api.BlendEquation(GL_FUNC_ADD);
  api.BlendFunc(GL_ONE, GL_ONE);
}

void RasterRenderer::Impl::emitters(const glm::mat4& vp) {
  if (!scene.has_emitters()) return;
  set_additive_state(api);
  emission_program.use();
  const EmissionUniforms& u = emission_uniforms;
  api.UniformMatrix4fv(u.view_projection, 1, GL_FALSE, glm::value_ptr(vp));
  gpu.draw_if([](const Material& m) { return m.emissive(); },
              [&](const Material& m) {
                api.Uniform3fv(u.emission, 1, glm::value_ptr(m.emission));
                api.Uniform1i(u.double_sided, m.double_sided ? 1 : 0);
                bind_material_texture(m.emissive_texture, u.has_texture);
              });
}

void RasterRenderer::Impl::shade(const Vpl& vpl, const glm::mat3& frame, const glm::mat4& vp) {
  target->bind();
  set_additive_state(api);
  vpl_program.use();
  const VplUniforms& u = vpl_uniforms;
  const float diagonal = scene.bounds.diagonal();
  const float dmin = vpl.clamped() ? options.clamp * diagonal : 0.0f;
  api.UniformMatrix4fv(u.view_projection, 1, GL_FALSE, glm::value_ptr(vp));
  api.Uniform3fv(u.position, 1, glm::value_ptr(vpl.position));
  api.Uniform3fv(u.normal, 1, glm::value_ptr(vpl.normal));
  api.Uniform3fv(u.intensity, 1, glm::value_ptr(vpl.intensity));
  api.Uniform1i(u.kind, static_cast<GLint>(vpl.kind));
  api.Uniform2f(u.spot_cos, vpl.cos_inner, vpl.cos_outer);
  api.Uniform1f(u.dmin2, dmin * dmin);
  api.Uniform1f(u.min_dist2, 1e-12f * diagonal * diagonal);
  api.UniformMatrix3fv(u.frame, 1, GL_FALSE, glm::value_ptr(frame));
  api.Uniform1f(u.bias_constant, 2e-4f * diagonal);
  api.Uniform1f(u.bias_texel, shadow.texel_angle());
  api.ActiveTexture(GL_TEXTURE0 + shadow_unit);
  api.BindTexture(GL_TEXTURE_CUBE_MAP, shadow.texture());
  gpu.draw([&](const Material& m) {
    api.Uniform3fv(u.base_color, 1, glm::value_ptr(m.base_color));
    bind_material_texture(m.base_color_texture, u.has_base_texture);
  });
}

RasterRenderer::RasterRenderer(const Scene& scene, const RasterOptions& options) {
  if (options.shadow_resolution < 1) throw Error("", "--shadow-res", "must be at least 1");
  if (!(options.clamp >= 0.0f)) throw Error("", "--clamp", "must be >= 0");
  const gl::Backend backend = options.backend == GlBackend::Egl      ? gl::Backend::Egl
                              : options.backend == GlBackend::OsMesa ? gl::Backend::OsMesa
                                                                     : gl::Backend::Auto;
  impl_ = std::make_unique<Impl>(scene, options, gl::create_context(backend, options.gl_device));
}

RasterRenderer::~RasterRenderer() = default;

std::string RasterRenderer::description() const {
  return impl_->context->backend() + ": " + impl_->context->renderer();
}

Image RasterRenderer::render(const View& view, const VplSet& vpls, RasterTimings* timings,
                             const Progress& progress) {
  Impl& im = *impl_;
  const auto t0 = std::chrono::steady_clock::now();
  if (!im.target || im.target->width() != view.width || im.target->height() != view.height)
    im.target = std::make_unique<gl::Target>(im.api, view.width, view.height);
  const glm::mat4 vp = view.projection * view.view;
  im.depth_prepass(vp);
  im.emitters(vp);
  std::size_t passes = 0;
  std::optional<gl::PassTimer> timer;
  if (im.options.gpu_timers) timer.emplace(im.api);
  for (std::size_t k = 0; k < vpls.vpls.size(); ++k) {
    const Vpl& vpl = vpls.vpls[k];
    if (carries_light(vpl)) {
      if (timer) timer->begin(gl::PassTimer::Shadow);
      const glm::mat3 frame = im.shadow.render(vpl, im.gpu);
      if (timer) timer->end(), timer->begin(gl::PassTimer::Shading);
      im.shade(vpl, frame, vp);
      if (timer) timer->end();
      ++passes;
    }
    if (progress) progress(k + 1, vpls.vpls.size());
  }
  im.context->check("raster passes");
  const auto t1 = std::chrono::steady_clock::now();
  Image image = im.target->read();
  im.context->check("readback");
  if (timings) {
    timings->passes_seconds = std::chrono::duration<double>(t1 - t0).count();
    timings->readback = seconds_since(t1);
    timings->passes = passes;
    if (timer) {
      const auto gpu = timer->seconds();
      timings->shadow_gpu = gpu[gl::PassTimer::Shadow];
      timings->shading_gpu = gpu[gl::PassTimer::Shading];
    }
  }
  return image;
}

} // namespace irad
