#include "walk/walls/wall_scan_ahead.h"

#include "core/util/parallel_rows.h"
#include "walk/walls/wall_cache.h"

#if defined(__linux__)
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace irad {

namespace {

// Thrown through cached_thinnest_wall by a scan that was stopped: nothing is written.
struct ScanStopped {};

// The calling thread at nice 19 (Linux keeps a nice value per thread). Best effort: where the
// kernel refuses, the scan runs at the usual priority.
void lowest_priority() {
#if defined(__linux__)
  setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), 19);
#endif
}

} // namespace

WallScanAhead::WallScanAhead(const Scene& scene, const RayScene& rays, float up_to,
                             std::filesystem::path folder)
    : scene_(scene), rays_(rays), up_to_(up_to), folder_(std::move(folder)),
      begun_(std::chrono::steady_clock::now()), thread_([this] { run(); }) {}

WallScanAhead::~WallScanAhead() {
  stop_.store(true);
  thread_.join();
}

// The scan on this thread, published so that get() can join it; its answer once every thread
// that joined has left it.
float WallScanAhead::scan_rows() {
  WallScan scan(scene_, rays_, up_to_);
  {
    const std::lock_guard lock(mutex_);
    scan_ = &scan;
  }
  changed_.notify_all();
  scan.work(&stop_);
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return joined_ == 0; });
  scan_ = nullptr;
  if (!scan.complete()) throw ScanStopped{};
  return scan.result();
}

void WallScanAhead::run() {
  lowest_priority();
  float answer = 0.0f;
  CacheResult cache;
  std::exception_ptr failed;
  try {
    answer = cached_thinnest_wall(scene_, rays_, up_to_, folder_, &cache,
                                  [this] { return scan_rows(); });
  } catch (const ScanStopped&) {
    // Not asked for: nothing kept.
  } catch (...) {
    failed = std::current_exception();
  }
  {
    const std::lock_guard lock(mutex_);
    answer_ = answer;
    cache_ = cache;
    failed_ = failed;
    finished_ = true;
    ended_ = std::chrono::steady_clock::now();
  }
  changed_.notify_all();
}

float WallScanAhead::get(CacheResult* result) {
  std::unique_lock lock(mutex_);
  bool joined = false;
  while (!finished_) {
    if (scan_ == nullptr || joined) {
      changed_.wait(lock);
      continue;
    }
    WallScan* scan = scan_;
    ++joined_;
    joined = true;
    lock.unlock();
    const auto workers = static_cast<int>(worker_count(0, scan->rows()));
    parallel_rows(workers, 0, [scan](int) { scan->work(); });
    lock.lock();
    --joined_;
    changed_.notify_all();
  }
  if (failed_) std::rethrow_exception(failed_);
  if (result) *result = cache_;
  return answer_;
}

double WallScanAhead::seconds() const {
  return std::chrono::duration<double>(ended_ - begun_).count();
}

} // namespace irad
