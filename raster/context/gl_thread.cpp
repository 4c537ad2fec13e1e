#include "raster/context/gl_thread.h"

namespace irad::gl {

GlThread::GlThread(std::unique_ptr<Context> context)
    : context_(std::move(context)), thread_([this] { loop(); }) {}

GlThread::~GlThread() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

std::future<void> GlThread::post(std::function<void(const GladGLContext&)> job) {
  std::packaged_task<void()> task([this, job = std::move(job)] {
    if (start_error_) std::rethrow_exception(start_error_);
    job(context_->api());
  });
  std::future<void> done = task.get_future();
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    jobs_.push_back(std::move(task));
  }
  wake_.notify_one();
  return done;
}

void GlThread::loop() {
  try {
    context_->make_current();
  } catch (...) {
    start_error_ = std::current_exception();
  }
  for (;;) {
    std::packaged_task<void()> task;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || !jobs_.empty(); });
      if (jobs_.empty()) break; // stop_, and every job has run
      task = std::move(jobs_.front());
      jobs_.pop_front();
    }
    task(); // an exception goes to the task's future
  }
  if (!start_error_) context_->release();
}

} // namespace irad::gl
