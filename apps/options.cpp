#include "apps/options.h"

#include "core/error.h"

#include <cstdio>
#include <filesystem>
#include <fmt/format.h>

namespace irad::apps {

std::pair<int, int> parse_size_option(const std::string& text) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X'))
    throw Error("", "--size", fmt::format("'{}' is not WIDTHxHEIGHT", text));
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    throw Error("", "--size", fmt::format("{}x{} is out of range (1..16384 per side)", w, h));
  return {w, h};
}

GlBackend parse_backend(const std::string& name) {
  if (name == "egl") return GlBackend::Egl;
  if (name == "osmesa") return GlBackend::OsMesa;
  if (name == "auto") return GlBackend::Auto;
  throw Error("", "--gl", "unknown backend '" + name + "' (auto, egl, osmesa)");
}

void require_writable(const std::string& path, const char* option) {
  namespace fs = std::filesystem;
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent))
    throw Error(path, option, fmt::format("output folder '{}' does not exist", parent.string()));
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::exists(status) && !fs::is_regular_file(status))
    throw Error(path, option, "it exists and is not a regular file");
}

} // namespace irad::apps
