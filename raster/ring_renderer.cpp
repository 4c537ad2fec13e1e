#include "raster/ring_renderer.h"

#include "core/util/error.h"
#include "raster/context/gl_context.h"
#include "raster/glsl/shaders.h"
#include "raster/image/gbuffer.h"
#include "raster/image/target.h"
#include "raster/passes/background.h"
#include "raster/passes/batched_passes.h"
#include "raster/passes/camera_passes.h"
#include "raster/passes/directional_pass.h"
#include "raster/passes/vpl_shader.h"
#include "raster/scene/gpu_scene.h"
#include "raster/shadow/shadow_cube.h"

#include <fmt/format.h>

namespace irad {

namespace {

constexpr GLint copy_unit = 6;

void check_memory(const RingOptions& o) {
  const std::size_t bytes = static_cast<std::size_t>(o.paths) * static_cast<std::size_t>(o.width) *
                            static_cast<std::size_t>(o.height) * 16u;
  if (o.paths == 0) throw Error("", "--paths", "must be at least 1");
  if (bytes > o.memory_limit)
    throw Error("", "--paths",
                fmt::format("a ring of {} path images of {}x{} needs {} MiB, over the limit of {} "
                            "MiB: use fewer paths or a smaller size",
                            o.paths, o.width, o.height, bytes >> 20, o.memory_limit >> 20));
}

} // namespace

struct RingRenderer::Impl {
  const Scene& scene;
  RingOptions options;
  std::unique_ptr<gl::Context> context;
  const GladGLContext& api;
  gl::GpuScene gpu;
  gl::ShadowCube shadow;
  gl::CameraPasses camera;
  gl::VplShader vpl_shader;
  gl::Target target;
  std::vector<gl::Texture> slots;
  std::vector<bool> filled;
  gl::Texture sum;
  gl::Framebuffer slot_fbo, sum_fbo;
  gl::VertexArray empty_vao;
  gl::ShaderProgram copy;
  std::unique_ptr<gl::DirectionalPass> directional; // only for scenes with directional lights
  std::unique_ptr<gl::Background> background;       // only for scenes that show one
  // The deferred passes (raster.batch > 1): a path image shades its G-buffer; nullptr: the
  // per-VPL passes (the reference).
  std::unique_ptr<gl::BatchedPasses> batched;
  std::unique_ptr<gl::GBuffer> gbuffer;
  int frames_since_resum = 0;
  std::size_t passes = 0, single_passes = 0;

  Impl(const Scene& s, const RingOptions& o, std::unique_ptr<gl::Context> c)
      : scene(s), options(o), context(std::move(c)), api(context->api()), gpu(api, s),
        shadow(api, shadow_resolution_for(o.raster.shadow_resolution, o.width, o.height), s.bounds,
               gpu.features()),
        camera(api, gpu.features()),
        vpl_shader(api, s, o.raster.clamp, o.raster.shadow_lod.planes != ShadowPlanes::Off),
        target(api, o.width, o.height), filled(o.paths, false),
        sum(gl::make_float_texture(api, o.width, o.height)), slot_fbo(gl::make_framebuffer(api)),
        sum_fbo(gl::make_framebuffer(api)), empty_vao(gl::make_vertex_array(api)),
        copy(api, "copy", gl::shaders::fullscreen_vertex, gl::shaders::copy_fragment),
        background(gl::Background::make(api, s)) {
    for (std::uint32_t i = 0; i < o.paths; ++i)
      slots.push_back(gl::make_float_texture(api, o.width, o.height));
    api.BindFramebuffer(GL_FRAMEBUFFER, slot_fbo.get());
    api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                             slots.front().get(), 0);
    api.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                target.depth());
    gl::check_framebuffer(api, "ring path-image framebuffer");
    api.BindFramebuffer(GL_FRAMEBUFFER, sum_fbo.get());
    api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, sum.get(), 0);
    gl::check_framebuffer(api, "ring sum framebuffer");
    clear_color();
    copy.use();
    api.Uniform1i(copy.uniform("u_source"), copy_unit);
    const int ortho = gl::ortho_resolution_for(o.raster.shadow_resolution, o.width, o.height);
    if (gl::has_directional_light(s))
      directional = std::make_unique<gl::DirectionalPass>(api, s, ortho);
    batched = gl::BatchedPasses::make(
        api, s, o.raster.clamp, o.raster.batch,
        shadow_resolution_for(o.raster.shadow_resolution, o.width, o.height),
        directional ? ortho : 0, o.raster.shadow_lod, false);
    if (batched)
      gbuffer = std::make_unique<gl::GBuffer>(api, o.width, o.height, target.depth(),
                                              gpu.features().glossy);
    context->check("ring set-up");
  }

  void viewport() const { api.Viewport(0, 0, options.width, options.height); }
  void clear_color() const {
    viewport();
    api.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    api.Clear(GL_COLOR_BUFFER_BIT);
  }
  // Adds (or subtracts) texture t to the bound framebuffer.
  void blend(const gl::Texture& t, bool subtract) const {
    api.Disable(GL_DEPTH_TEST);
    api.Enable(GL_BLEND);
    api.BlendEquation(subtract ? GL_FUNC_REVERSE_SUBTRACT : GL_FUNC_ADD);
    api.BlendFunc(GL_ONE, GL_ONE);
    copy.use();
    api.ActiveTexture(GL_TEXTURE0 + copy_unit);
    api.BindTexture(GL_TEXTURE_2D, t.get());
    api.BindVertexArray(empty_vao.get());
    api.DrawArrays(GL_TRIANGLES, 0, 3);
    api.BlendEquation(GL_FUNC_ADD);
    api.BindTexture(GL_TEXTURE_2D, 0);
  }
  void bind_sum() const {
    api.BindFramebuffer(GL_FRAMEBUFFER, sum_fbo.get());
    viewport();
  }
  void sum_ring_into_bound() const {
    clear_color();
    for (std::size_t s = 0; s < slots.size(); ++s)
      if (filled[s]) blend(slots[s], false);
  }
};

RingRenderer::RingRenderer(const Scene& scene, const RingOptions& options) {
  check_memory(options);
  impl_ = std::make_unique<Impl>(
      scene, options, gl::create_context(options.raster.backend, options.raster.gl_device));
  impl_->context->release();
}

// The GL objects are deleted in their own context.
RingRenderer::~RingRenderer() {
  if (impl_) gl::make_current_for_teardown(*impl_->context);
}

void RingRenderer::scene_changed() {
  const gl::CurrentScope current(*impl_->context);
  impl_->gpu.update_vertices();
}

std::uint32_t RingRenderer::slots() const {
  return impl_->options.paths;
}
std::size_t RingRenderer::passes() const {
  return impl_->passes;
}
std::size_t RingRenderer::single_passes() const {
  return impl_->single_passes;
}

void RingRenderer::replace(std::uint32_t path, const std::vector<Vpl>& vpls, const View& view,
                           const std::vector<VplLobe>& lobes) {
  Impl& im = *impl_;
  const gl::CurrentScope current(*im.context);
  const std::size_t s = path % im.options.paths;
  if (im.filled[s]) {
    im.bind_sum();
    im.blend(im.slots[s], true); // the image leaving the ring
  }
  // The new path image: depth of the current view, then each VPL's shadow cube and pass.
  const glm::mat4 vp = view.projection * view.view;
  const auto bind_slot = [&] {
    im.api.BindFramebuffer(GL_FRAMEBUFFER, im.slot_fbo.get());
    im.api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                                im.slots[s].get(), 0);
    im.viewport();
  };
  im.api.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  im.api.ClearDepth(1.0);
  im.api.DepthMask(GL_TRUE);
  if (im.gbuffer) {
    im.camera.gbuffer(*im.gbuffer, vp, gl::eye_uniform(view), im.gpu); // its depth: the slot's
    bind_slot();
    im.api.Clear(GL_COLOR_BUFFER_BIT);
  } else {
    bind_slot();
    im.api.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    im.camera.depth(vp, im.gpu);
  }
  if (im.directional) im.directional->forget();
  // Batched: every VPL in the deferred passes but the directional ones when no orthographic
  // atlas fits; the per-VPL passes (batch 1, the reference) one by one.
  std::vector<const Vpl*> many;
  std::vector<Vpl> alone;
  for (const Vpl& vpl : vpls) {
    const bool own = vpl.kind == VplKind::Directional && !(im.batched && im.batched->directional());
    if (im.batched && !own)
      many.push_back(&vpl);
    else
      alone.push_back(vpl);
  }
  im.vpl_shader.set_eye(gl::eye_uniform(view));
  im.vpl_shader.set_lobes(&lobes);
  if (im.batched) {
    im.batched->set_lobes(&lobes);
    im.passes += im.batched->draw(many, [](const Vpl&) { return 0; },
                                  {im.gbuffer.get(), nullptr, bind_slot}, im.gpu, nullptr, {});
    im.batched->set_lobes(nullptr);
  }
  for (const Vpl& vpl : alone) {
    if (!vpl.carries_light()) continue;
    if (vpl.kind == VplKind::Directional) {
      im.directional->shadow(vpl, im.gpu);
      bind_slot();
      im.directional->draw(vpl, vp, true, im.gpu);
    } else {
      const glm::mat3 frame = im.shadow.render(vpl, im.gpu);
      bind_slot();
      im.vpl_shader.draw(vpl, im.shadow, frame, vp, true, im.gpu);
    }
    ++im.passes;
    ++im.single_passes;
  }
  im.vpl_shader.set_lobes(nullptr);
  im.bind_sum();
  im.blend(im.slots[s], false); // the image arriving
  im.filled[s] = true;
  if (im.options.resum_every > 0 && ++im.frames_since_resum >= im.options.resum_every) resum();
  im.context->check("ring path image");
}

void RingRenderer::resum() {
  Impl& im = *impl_;
  const gl::CurrentScope current(*im.context);
  im.bind_sum();
  im.sum_ring_into_bound();
  im.frames_since_resum = 0;
}

Image RingRenderer::frame(const View& view) {
  Impl& im = *impl_;
  const gl::CurrentScope current(*im.context);
  im.target.bind();
  im.api.ClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  im.api.ClearDepth(1.0);
  im.api.DepthMask(GL_TRUE);
  im.api.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  im.blend(im.sum, false);
  const glm::mat4 vp = view.projection * view.view;
  im.camera.depth(vp, im.gpu);
  im.camera.emitters(vp, im.scene, im.gpu);
  if (im.background) im.background->draw(view, vp);
  im.context->check("ring frame");
  return im.target.read();
}

Image RingRenderer::exact_sum() {
  Impl& im = *impl_;
  const gl::CurrentScope current(*im.context);
  im.target.bind();
  im.sum_ring_into_bound();
  return im.target.read();
}

} // namespace irad
