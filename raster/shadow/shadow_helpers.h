#pragma once
// Shadow atlases drawn on helper threads, each with a GL context of its own that shares the
// renderer's objects (raster/context/gl_thread.h), while the renderer's context shades the
// batches already drawn. On llvmpipe the thread that issues a context's draws runs their vertex
// stage and triangle set-up, then waits while the rasterizer threads finish the scene: the
// shadow faces of a game level (zdm2: 16k triangles per VPL) kept one core busy at 63 % and the
// rasterizer threads at 36 %. With two helpers one bins its atlas while the other's is
// rasterized. Each helper draws through a ShadowAtlas of its own (the same program, hierarchy
// and faces as the renderer's), so an atlas is the same texel for texel whichever context drew
// it.
#include "core/lights/vpl.h"
#include "raster/context/gl_thread.h"
#include "raster/context/pass_timer.h"
#include "raster/scene/gpu_scene.h"
#include "raster/shadow/shadow_atlas.h"

#include <future>
#include <memory>
#include <vector>

namespace irad::gl {

class ShadowHelpers {
public:
  // ShadowAtlas's constructor's arguments, for the helpers' atlases.
  struct AtlasShape {
    int resolution = 0, batch = 0, blocks = 0;
    Bounds bounds;
    MaterialFeatures features;
    ShadowLodOptions lod;
  };
  // What a helper drew: ShadowAtlas::render's outputs, its textures and the hierarchy's triangles.
  struct Drawn {
    std::vector<glm::mat3> frames;
    std::vector<float> fars;
    std::vector<glm::ivec4> blocks;
    GLuint texture = 0, gradient = 0;
    std::size_t triangles = 0;
    GLsync fence = nullptr; // signals when the atlas is complete (finish() waits for it)
  };
  // A batch's atlas on its way.
  struct Job {
    std::vector<const Vpl*> vpls;
    std::future<void> done;
    Drawn drawn;
  };

  // `count` threads with contexts shared with `context` (current on the calling thread), each
  // making an atlas of `shape` there. lod: the renderer's hierarchy, already built (its get()
  // returned: the helpers only read it), or nullptr when the faces draw every triangle.
  ShadowHelpers(Context& context, int count, const AtlasShape& shape, LodProvider* lod);
  // Destroys the atlases on their threads.
  ~ShadowHelpers();
  ShadowHelpers(const ShadowHelpers&) = delete;
  ShadowHelpers& operator=(const ShadowHelpers&) = delete;

  int count() const { return static_cast<int>(threads_.size()); }

  // A helper draws its jobs into kSlots atlases in turn: a job overwrites the atlas of the
  // kSlots-th job before it on the same helper. With at most kAhead jobs started and not yet
  // shaded per helper, that one's shading was issued a batch or more before.
  static constexpr int kSlots = 3;
  static constexpr int kAhead = 2;

  // Starts drawing the cubes of job.vpls (as ShadowAtlas::render; n <= shape.batch) on helper
  // `helper`, once the calling context's commands so far have completed (a fence: the vertex
  // data, the hierarchy and the reads of the atlas this draw overwrites). Start the kSlots-th job
  // after one only once that one's reads were issued. timed: the helper's GL timer measures the
  // draw.
  void start(int helper, Job& job, const GpuScene& gpu, bool timed);
  // Waits until the job's atlas is complete on the GPU (the calling context may then read it);
  // rethrows a helper's error.
  const Drawn& finish(Job& job) const;
  // For a job whose atlas will not be read (draw() stopped early, or failed): waits until its
  // helper is done with it and drops what it made. Nothing for a finished or unstarted job.
  void abandon(Job& job) const noexcept;
  // Seconds the helpers' timers measured since the last call (PassTimer::Shadow); waits for them.
  double take_timed_seconds();

private:
  // Destroys the atlases on their threads (the destructor; a constructor that failed).
  void release() noexcept;
  struct Helper {
    std::unique_ptr<GlThread> thread;
    // Made, used and destroyed on the thread.
    std::unique_ptr<ShadowAtlas> atlas;
    std::unique_ptr<PassTimer> timer;
  };
  const GladGLContext* api_;
  std::vector<Helper> threads_;
};

} // namespace irad::gl
