#include "raster/shadow/shadow_helpers.h"

namespace irad::gl {

namespace {

// Waits until `fence` (made by another context of the share group) has signalled, then deletes it.
void wait_and_delete(const GladGLContext& api, GLsync fence) {
  constexpr GLuint64 kSecond = 1000000000;
  while (api.ClientWaitSync(fence, 0, kSecond) == GL_TIMEOUT_EXPIRED) {
  }
  api.DeleteSync(fence);
}

} // namespace

ShadowHelpers::ShadowHelpers(Context& context, int count, const AtlasShape& shape, LodProvider* lod)
    : api_(&context.api()) {
  if (lod != nullptr)
    if (const ShadowLod* hierarchy = lod->get()) hierarchy->share_with_contexts();
  threads_.resize(static_cast<std::size_t>(count));
  std::vector<std::future<void>> made;
  try {
    for (Helper& h : threads_) {
      h.thread = std::make_unique<GlThread>(context.make_shared());
      made.push_back(h.thread->post([&h, &shape, lod](const GladGLContext& api) {
        h.atlas =
            std::make_unique<ShadowAtlas>(api, shape.resolution, shape.batch, shape.blocks,
                                          shape.bounds, shape.features, shape.lod, lod, kSlots);
        h.timer = std::make_unique<PassTimer>(api);
      }));
    }
    for (std::future<void>& m : made) m.get(); // the programs compile on all threads at once
  } catch (...) {
    for (std::future<void>& m : made)
      if (m.valid()) m.wait();
    release();
    throw;
  }
}

ShadowHelpers::~ShadowHelpers() {
  release();
}

void ShadowHelpers::release() noexcept {
  for (Helper& h : threads_) {
    if (!h.thread) continue;
    try {
      h.thread->run([&h](const GladGLContext&) {
        h.timer.reset();
        h.atlas.reset();
      });
    } catch (...) { // a context that never became current: its objects go with it
    }
  }
}

void ShadowHelpers::start(int helper, Job& job, const GpuScene& gpu, bool timed) {
  Helper& h = threads_.at(static_cast<std::size_t>(helper));
  GLsync ready = api_->FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  api_->Flush(); // the fence must reach the GPU for another context's wait to end
  job.done = h.thread->post([&h, &job, &gpu, ready, timed](const GladGLContext& api) {
    wait_and_delete(api, ready);
    Drawn& d = job.drawn;
    if (timed) h.timer->begin(PassTimer::Shadow);
    h.atlas->render(job.vpls.data(), static_cast<int>(job.vpls.size()), gpu, d.frames, d.fars,
                    d.blocks);
    if (timed) h.timer->end();
    d.texture = h.atlas->texture();
    d.gradient = h.atlas->gradient_texture();
    d.triangles = h.atlas->cluster_triangles();
    d.fence = api.FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    api.Flush(); // the fence must reach the GPU for another context's wait to end
  });
}

const ShadowHelpers::Drawn& ShadowHelpers::finish(Job& job) const {
  job.done.get();
  wait_and_delete(*api_, job.drawn.fence);
  job.drawn.fence = nullptr;
  return job.drawn;
}

void ShadowHelpers::abandon(Job& job) const noexcept {
  if (!job.done.valid()) return;
  job.done.wait();
  if (job.drawn.fence) api_->DeleteSync(job.drawn.fence); // a pending fence goes once signalled
  job.drawn.fence = nullptr;
  job.done = {};
}

double ShadowHelpers::take_timed_seconds() {
  double total = 0.0;
  for (Helper& h : threads_)
    h.thread->run([&h, &total](const GladGLContext& api) {
      total += h.timer->seconds()[PassTimer::Shadow];
      h.timer = std::make_unique<PassTimer>(api);
    });
  return total;
}

} // namespace irad::gl
