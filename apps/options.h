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

} // namespace irad::apps
