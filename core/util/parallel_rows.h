#pragma once
// Runs body(row) for every row in [0, rows) on `threads` threads (0: all cores), rows handed out
// one at a time from a shared counter. body must only write data of its own row and must not
// throw (an exception escaping a worker thread would terminate the program).
#include <algorithm>
#include <atomic>
#include <functional>
#include <thread>
#include <vector>

namespace irad {

inline void parallel_rows(int rows, unsigned threads, const std::function<void(int)>& body,
                          const std::function<void(int done)>& on_main_thread_progress = {}) {
  std::atomic<int> next{0}, done{0};
  auto work = [&](bool main) {
    for (int r = next++; r < rows; r = next++) {
      body(r);
      const int d = ++done;
      if (main && on_main_thread_progress) on_main_thread_progress(d);
    }
  };
  threads = std::max(1u, threads ? threads : std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work, false);
  work(true);
  for (std::thread& t : pool) t.join();
}

} // namespace irad
