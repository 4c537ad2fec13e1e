#pragma once
// Wall-clock seconds of named stages, in the order they ran: what a one-time set-up (the shadow
// hierarchy, the GL upload) costs, part by part, for --stats (seconds.raster_setup).
#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace irad {

class StageTimes {
public:
  using Clock = std::chrono::steady_clock;

  // Adds `seconds` to the stage `name` (appended when new).
  void add(const std::string& name, double seconds) {
    for (auto& [n, s] : stages_)
      if (n == name) {
        s += seconds;
        return;
      }
    stages_.emplace_back(name, seconds);
  }
  // Adds every stage of `other`, its names prefixed by `prefix`.
  void add(const std::string& prefix, const StageTimes& other) {
    for (const auto& [n, s] : other.stages_) add(prefix + n, s);
  }
  // Adds the time since `start` to `name` and returns now (the next stage's start).
  Clock::time_point lap(const std::string& name, Clock::time_point start) {
    const Clock::time_point now = Clock::now();
    add(name, std::chrono::duration<double>(now - start).count());
    return now;
  }
  const std::vector<std::pair<std::string, double>>& stages() const { return stages_; }

private:
  std::vector<std::pair<std::string, double>> stages_;
};

} // namespace irad
