#include "apps/options.h"

#include "core/scene/scene_builder.h"
#include "core/util/error.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <glm/glm.hpp>

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

ShadowLodMode parse_shadow_lod(const std::string& name) {
  if (name == "on") return ShadowLodMode::On;
  if (name == "cull") return ShadowLodMode::Cull;
  if (name == "off") return ShadowLodMode::Off;
  throw Error("", "--shadow-lod", "unknown mode '" + name + "' (on, cull, off)");
}

Visibility parse_visibility(const std::string& name) {
  if (name == "auto") return Visibility::Auto;
  if (name == "maps") return Visibility::Maps;
  if (name == "rays") return Visibility::Rays;
  throw Error("", "--visibility", "unknown mode '" + name + "' (auto, maps, rays)");
}

ShadowPlanes parse_shadow_planes(const std::string& name) {
  if (name == "auto") return ShadowPlanes::Auto;
  if (name == "on") return ShadowPlanes::On;
  if (name == "off") return ShadowPlanes::Off;
  throw Error("", "--shadow-planes", "unknown mode '" + name + "' (auto, on, off)");
}

CameraLodMode parse_camera_lod(const std::string& name) {
  if (name == "on") return CameraLodMode::On;
  if (name == "off") return CameraLodMode::Off;
  throw Error("", "--camera-lod", "unknown mode '" + name + "' (on, off)");
}

std::optional<std::uint64_t> parse_count_or_auto(const std::string& text, const char* option,
                                                 std::uint64_t min, std::uint64_t max) {
  if (text == "auto") return std::nullopt;
  std::uint64_t value = 0;
  const bool digits =
      !text.empty() && text.size() <= 19 &&
      std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  if (digits) value = std::stoull(text);
  if (!digits || value < min || value > max)
    throw Error("", option,
                fmt::format("'{}' is not auto or a whole number in [{}, {}]", text, min, max));
  return value;
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

void add_look_at_options(CLI::App& cmd, LookAtArgs& args) {
  cmd.add_option("--look-from", args.from, "Own camera: its position X,Y,Z (with --look-at)");
  cmd.add_option("--look-at", args.at, "Own camera: the point X,Y,Z it looks at");
  cmd.add_option("--up", args.up, "Own camera: the up direction X,Y,Z (default: 0,1,0)");
  cmd.add_option("--yfov", args.yfov, "Own camera: vertical field of view in degrees (39.6)");
}

namespace {

glm::vec3 parse_vec3(const std::string& text, const char* option) {
  float x = 0, y = 0, z = 0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%f,%f,%f%c", &x, &y, &z, &extra) != 3 || !std::isfinite(x) ||
      !std::isfinite(y) || !std::isfinite(z))
    throw Error("", option, fmt::format("'{}' is not X,Y,Z (three finite numbers)", text));
  return {x, y, z};
}

float parse_yfov_degrees(const std::string& text) {
  if (text.empty()) return 39.6f;
  float deg = 0;
  char extra = 0;
  if (std::sscanf(text.c_str(), "%f%c", &deg, &extra) != 1)
    throw Error("", "--yfov", fmt::format("'{}' is not a number of degrees", text));
  if (!(deg > 0.0f && deg < 180.0f))
    throw Error("", "--yfov", fmt::format("must be in (0, 180) degrees, got {}", text));
  return deg;
}

} // namespace

std::optional<Camera> parse_look_at(const LookAtArgs& args, const std::string& camera) {
  if (args.from.empty() && args.at.empty() && args.up.empty() && args.yfov.empty())
    return std::nullopt;
  if (args.from.empty())
    throw Error("", "--look-from", "missing (needed by --look-at, --up, --yfov)");
  if (args.at.empty()) throw Error("", "--look-at", "missing (needed by --look-from)");
  if (!camera.empty()) throw Error("", "--look-from", "cannot be combined with --camera");
  const glm::vec3 from = parse_vec3(args.from, "--look-from");
  const glm::vec3 at = parse_vec3(args.at, "--look-at");
  const glm::vec3 up = args.up.empty() ? glm::vec3(0, 1, 0) : parse_vec3(args.up, "--up");
  const float yfov = parse_yfov_degrees(args.yfov);
  if (from == at) throw Error("", "--look-at", "equals --look-from (no view direction)");
  const glm::vec3 side = glm::cross(up, glm::normalize(from - at));
  if (!(glm::length(side) > 1e-6f * glm::length(up)))
    throw Error("", "--up",
                fmt::format("'{}' is zero or parallel to the view direction",
                            args.up.empty() ? "0,1,0 (the default)" : args.up));
  Camera c = look_at(from, at, up, glm::radians(yfov)); // the checks above keep it from failing
  c.name = "--look-from";
  return c;
}

std::string image_options(const CLI::App& cmd, const std::vector<std::string>& ignored) {
  std::string text;
  for (const CLI::Option* o : cmd.get_options()) {
    const std::string name = o->get_lnames().empty() ? o->get_name() : "--" + o->get_lnames()[0];
    if (o->get_positional() || name == "--help" ||
        std::find(ignored.begin(), ignored.end(), name) != ignored.end())
      continue;
    std::string value;
    if (o->count() == 0) {
      value = o->get_default_str();
    } else {
      for (const std::string& r : o->results()) value += (value.empty() ? "" : ",") + r;
    }
    text += (text.empty() ? "" : ";") + name + "=" + value;
  }
  return text;
}

} // namespace irad::apps
