#include "apps/progress_line.h"

#include <cstdio>

namespace irad::apps {

ProgressLine::~ProgressLine() {
  if (enabled_ && drawn_) std::fputs("\r\033[K", stderr);
}

void ProgressLine::operator()(std::size_t done, std::size_t total) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (done != total && now - last_ < std::chrono::milliseconds(100)) return;
  last_ = now;
  drawn_ = true;
  std::fprintf(stderr, "\rirad: rendering %zu/%zu (%.0f%%)", done, total,
               total ? 100.0 * static_cast<double>(done) / static_cast<double>(total) : 100.0);
  std::fflush(stderr);
}

} // namespace irad::apps
