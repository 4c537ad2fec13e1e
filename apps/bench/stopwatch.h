#pragma once
// The bench's clock: seconds of the steady clock since a time point.
#include <chrono>

namespace irad::apps {

using Clock = std::chrono::steady_clock;

inline double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

} // namespace irad::apps
