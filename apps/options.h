#pragma once
// Option values shared by the subcommands.
#include "core/scene/scene.h"
#include "raster/raster_renderer.h"

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace CLI {
class App;
}

namespace irad::apps {

// "WIDTHxHEIGHT", 1..16384 per side; throws irad::Error naming --size.
std::pair<int, int> parse_size_option(const std::string& text);
// "auto", "egl" or "osmesa".
GlBackend parse_backend(const std::string& name);
// --shadow-lod: on, cull, off (RasterOptions::shadow_lod).
ShadowLodMode parse_shadow_lod(const std::string& name);
// --visibility: auto, maps, rays (RasterOptions::visibility).
Visibility parse_visibility(const std::string& name);
// --shadow-planes: auto, on, off (RasterOptions::shadow_lod.planes).
ShadowPlanes parse_shadow_planes(const std::string& name);
// --camera-lod: on, off (RasterOptions::camera_lod).
CameraLodMode parse_camera_lod(const std::string& name);
// "auto" (nullopt) or a whole number in [min, max] (`irad render --paths`, `--clusters`); throws
// irad::Error naming `option` for anything else.
std::optional<std::uint64_t> parse_count_or_auto(const std::string& text, const char* option,
                                                 std::uint64_t min, std::uint64_t max);
// Throws irad::Error naming `option` unless `path` can be written: its folder exists and it is
// not something other than a regular file (a folder, a device).
void require_writable(const std::string& path, const char* option);

// The command line's own camera, as given (empty: not given):
// --look-from X,Y,Z --look-at X,Y,Z [--up X,Y,Z] [--yfov DEG].
struct LookAtArgs {
  std::string from, at, up, yfov;
};
// Adds the four options to a subcommand.
void add_look_at_options(CLI::App& cmd, LookAtArgs& args);
// nullopt when none of the four is given; else their camera, named "--look-from": a right-handed
// frame looking down -z with y up (z = normalize(from - at), x = normalize(cross(up, z)),
// y = cross(z, x)), up (0,1,0) and yfov 39.6 degrees (Blender's 50 mm lens on 36 mm) unless
// given, no aspect ratio, znear 0 (fitted to the scene). Throws irad::Error with one line naming
// the option: a value that is not three finite numbers (or a number), --look-from without
// --look-at or the reverse (or --up/--yfov without them), from == at, up zero or parallel to the
// view direction, yfov outside (0, 180) degrees, or `camera` (the --camera value) not empty.
std::optional<Camera> parse_look_at(const LookAtArgs& args, const std::string& camera);

// The options of `cmd` that change the image, canonical: "NAME=VALUE" per option in the order
// of their definition, joined by ';'; VALUE is what the command line gave (several values
// joined by ',') or the default. Options named in `ignored` (long names, e.g. "--threads") and
// the positional arguments are left out. Two command lines that give the same values, or leave
// them at the default, give the same text (a value spelled differently, 0.05 and .05, differs).
std::string image_options(const CLI::App& cmd, const std::vector<std::string>& ignored);

} // namespace irad::apps
