#pragma once
// Environment maps from files and the --env colour, checked: what core/environment/environment.h's
// Environment takes (linear RGB radiance, width == 2 height, every texel finite and >= 0).
#include "core/image/image.h"

#include <filesystem>
#include <glm/glm.hpp>
#include <string>

namespace irad {

// The widest map read (a 16384 x 8192 map is 2 GiB of float RGBA).
inline constexpr int kMaxEnvironmentWidth = 16384;

// An equirectangular radiance map: OpenEXR (.exr: R, G, B as float) or Radiance HDR (.hdr, .pic:
// RGBE, "-Y H +X W" layout; EXPOSURE lines are ignored); extensions are case-insensitive.
// Returns linear RGB with alpha 1, row 0 at the top (the zenith, core/environment/environment.h).
// Throws irad::Error(path, option, ...) on one line for: a file that cannot be read (saying why),
// an unknown extension, data that does not decode, a width over kMaxEnvironmentWidth, a map that is
// not 2:1, an HDR file whose pixels are shorter than its size needs, and the first texel (in row
// order) that is NaN, infinite or negative. Known limit: a run-length coded HDR file cut short,
// but still longer than the shortest coding of its size, reads its missing texels as black
// (stb_image reports no error).
Image read_environment_map(const std::filesystem::path& path, const std::string& option);

// "R,G,B": a uniform environment's radiance; three finite numbers >= 0. All zero is refused
// ("is black: no light"): leaving the option out is how to ask for no environment.
glm::vec3 parse_env_color(const std::string& text, const std::string& option);

} // namespace irad
