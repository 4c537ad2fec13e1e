#pragma once
// Runs body(row) for every row in [0, rows) on `threads` threads (0: all cores), rows handed out
// one at a time from a shared counter. body must only write data of its own row and must not
// throw (an exception escaping a worker thread would terminate the program).
#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
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

// The threads parallel_rows and parallel_tasks run for `threads` (0: all cores) and `tasks`.
inline unsigned worker_count(unsigned threads, int tasks) {
  threads = std::max(1u, threads ? threads : std::thread::hardware_concurrency());
  return std::max(1u, std::min(threads, static_cast<unsigned>(std::max(tasks, 1))));
}

// Runs body(task, worker) for every task in [0, tasks) on worker_count(threads, tasks) threads,
// tasks handed out in order from a shared counter; worker in [0, worker_count) names the thread,
// so that each can keep its own scratch. body must only write its task's data; an exception it
// throws stops the tasks not yet begun and is rethrown here once every thread has finished.
inline void parallel_tasks(int tasks, unsigned threads,
                           const std::function<void(int task, unsigned worker)>& body) {
  std::atomic<int> next{0};
  std::mutex failed_mutex;
  std::exception_ptr failed;
  auto work = [&](unsigned worker) {
    for (int t = next++; t < tasks; t = next++) {
      try {
        body(t, worker);
      } catch (...) {
        const std::lock_guard lock(failed_mutex);
        if (!failed) failed = std::current_exception();
        next = tasks;
      }
    }
  };
  const unsigned workers = worker_count(threads, tasks);
  std::vector<std::thread> pool;
  for (unsigned w = 1; w < workers; ++w) pool.emplace_back(work, w);
  work(0);
  for (std::thread& t : pool) t.join();
  if (failed) std::rethrow_exception(failed);
}

// The elements of one chunk of parallel_chunks: chunk k is [k kParallelChunk, (k + 1)
// kParallelChunk), the last one shorter.
inline constexpr std::size_t kParallelChunk = std::size_t{1} << 16;

// Runs body(first, end) over [0, count) chunk by chunk on all cores, one thread where there are
// fewer than two chunks (a small array is not worth the threads): the loaders' and builders'
// per-element loops. body must only write its own elements and must not throw.
inline void parallel_chunks(std::size_t count,
                            const std::function<void(std::size_t first, std::size_t end)>& body) {
  const std::size_t chunks = (count + kParallelChunk - 1) / kParallelChunk;
  parallel_rows(static_cast<int>(chunks), chunks > 1 ? 0u : 1u, [&](int c) {
    const std::size_t first = static_cast<std::size_t>(c) * kParallelChunk;
    body(first, std::min(count, first + kParallelChunk));
  });
}

} // namespace irad
