#pragma once
// The thinnest-wall scan (walk/walls/thin_walls.h, through its cache walk/walls/wall_cache.h) begun
// before its answer is wanted, on one thread of the lowest priority (nice 19), so that it takes
// only cores nothing else wants. Between the clustering and the first shadow maps, llvmpipe runs
// the GL upload and the G-buffer's vertex stage on the asking thread alone, leaving the other core
// idle (about a second on the 10M-triangle sphere box, whose scan takes a second on both
// cores); the scan fills it. When the answer is wanted, the rows left are scanned on every core,
// the asking thread among them. The answer is thinnest_wall's, whichever threads took which
// rows, and the cache is read and written as cached_thinnest_wall does.
#include "core/mesh/hierarchy/cluster_cache.h"
#include "walk/walls/thin_walls.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <filesystem>
#include <mutex>
#include <thread>

namespace irad {

class WallScanAhead {
public:
  // Begins cached_thinnest_wall(scene, rays, up_to, folder) on its own thread. The scene and the
  // rays must outlive this object.
  WallScanAhead(const Scene& scene, const RayScene& rays, float up_to,
                std::filesystem::path folder);
  // Stops a scan whose answer was not asked for (nothing is written then) and waits for its
  // thread.
  ~WallScanAhead();
  WallScanAhead(const WallScanAhead&) = delete;
  WallScanAhead& operator=(const WallScanAhead&) = delete;

  // The answer, cached_thinnest_wall's, and in `result` what the cache did: the rows left
  // scanned on all cores, the calling thread among them. Rethrows what the scan threw.
  float get(CacheResult* result = nullptr);
  // Seconds from the scan's start to its answer (on the scan's thread); valid after get().
  double seconds() const;

private:
  void run(); // the thread's body
  float scan_rows();

  const Scene& scene_;
  const RayScene& rays_;
  const float up_to_;
  const std::filesystem::path folder_;
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::condition_variable changed_;
  // Under mutex_: the scan in progress (nullptr before and after it), the threads that joined
  // it, and what the thread ended with.
  WallScan* scan_ = nullptr;
  int joined_ = 0;
  bool finished_ = false;
  float answer_ = 0.0f;
  CacheResult cache_;
  std::exception_ptr failed_;
  std::chrono::steady_clock::time_point begun_, ended_;
  std::thread thread_; // last: begins once every member above exists
};

} // namespace irad
