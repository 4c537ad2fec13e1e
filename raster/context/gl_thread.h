#pragma once
// A thread of its own with a GL context current on it (Context::make_shared: it shares the
// creator's buffers, textures, programs and sync objects), running posted jobs one after another.
// On llvmpipe a context's draws run their vertex stage and triangle set-up on the thread that
// issues them, and the thread then waits while the rasterizer threads finish its scene: two
// contexts on two threads bin one scene while the other's is rasterized (the shadow atlases of
// raster/shadow/shadow_helpers.h).
//
// A job that changes an object the creator's context then reads must finish that work on the GPU
// before it returns (glFinish, or a fence the reader waits on), and the reader binds the object
// again before it reads it (OpenGL 4.6 core, 5.3.3: changes made by another context).
#include "raster/context/gl_context.h"

#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <thread>

namespace irad::gl {

class GlThread {
public:
  // Starts the thread and makes `context` current on it.
  explicit GlThread(std::unique_ptr<Context> context);
  // Runs the jobs already posted, then releases the context on the thread and joins it.
  ~GlThread();
  GlThread(const GlThread&) = delete;
  GlThread& operator=(const GlThread&) = delete;

  // Queues `job`, to run on the thread with the context current. The future is ready when it
  // has run, and holds its exception (irad::Error, or one made current on the thread failed).
  std::future<void> post(std::function<void(const GladGLContext&)> job);
  // post(job), then waits for it and rethrows its exception.
  void run(std::function<void(const GladGLContext&)> job) { post(std::move(job)).get(); }

private:
  void loop();

  std::unique_ptr<Context> context_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::packaged_task<void()>> jobs_;
  bool stop_ = false;
  std::exception_ptr start_error_; // make_current failed: every job rethrows it
  std::thread thread_;             // last: started once the members above exist
};

} // namespace irad::gl
