#pragma once
// A logger is an object handed to whoever needs to warn; there is no global logger.
// Warnings go to stderr unless quiet; identical warnings are reported once per logger.
#include <functional>
#include <set>
#include <string>

namespace irad {

class Log {
public:
  using Sink = std::function<void(const std::string&)>;
  Log(); // writes "irad: warning: ..." lines to stderr
  explicit Log(Sink sink) : sink_(std::move(sink)) {}

  void set_quiet(bool quiet) { quiet_ = quiet; }
  bool quiet() const { return quiet_; }
  void warn(const std::string& message);
  void info(const std::string& message);
  int warnings() const { return warnings_; }

private:
  Sink sink_;
  bool quiet_ = false;
  int warnings_ = 0;
  std::set<std::string> seen_;
};

} // namespace irad
