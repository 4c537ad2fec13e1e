#include "core/util/log.h"

#include <cstdio>

namespace irad {

Log::Log()
    : sink_([](const std::string& line) { std::fprintf(stderr, "irad: %s\n", line.c_str()); }) {}

void Log::warn(const std::string& message) {
  ++warnings_;
  if (!seen_.insert(message).second) return;
  if (!quiet_) sink_("warning: " + message);
}

void Log::info(const std::string& message) {
  if (!quiet_) sink_(message);
}

} // namespace irad
