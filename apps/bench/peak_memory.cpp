#include "apps/bench/peak_memory.h"

#include <fstream>
#include <string>

namespace irad::apps {

void reset_peak_memory() {
  std::ofstream clear("/proc/self/clear_refs");
  if (clear) clear << "5";
}

double peak_memory_mib() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) != 0) continue;
    try {
      return std::stod(line.substr(6)) / 1024.0; // kB
    } catch (const std::exception&) {
      return 0.0;
    }
  }
  return 0.0;
}

} // namespace irad::apps
