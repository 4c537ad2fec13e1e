#pragma once
// Option values shared by the subcommands.
#include "raster/raster_renderer.h"

#include <string>
#include <utility>

namespace irad::apps {

// "WIDTHxHEIGHT", 1..16384 per side; throws irad::Error naming --size.
std::pair<int, int> parse_size_option(const std::string& text);
// "auto", "egl" or "osmesa".
GlBackend parse_backend(const std::string& name);
// Throws irad::Error naming `option` unless `path` can be written: its folder exists and it is
// not something other than a regular file (a folder, a device).
void require_writable(const std::string& path, const char* option);

} // namespace irad::apps
