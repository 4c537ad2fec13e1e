#pragma once
// The terminal's progress line: "irad: rendering DONE/TOTAL (P%)" rewritten on stderr at most
// ~10 times per second (and at the end); the destructor erases it.
#include <chrono>
#include <cstddef>

namespace irad::apps {

class ProgressLine {
public:
  explicit ProgressLine(bool enabled) : enabled_(enabled) {}
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  bool enabled() const { return enabled_; }
  void operator()(std::size_t done, std::size_t total);

private:
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_{};
};

} // namespace irad::apps
