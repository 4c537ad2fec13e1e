#include "apps/lighting_options.h"

#include "core/environment/environment_file.h"

#include <CLI/CLI.hpp>

namespace irad::apps {

void add_lighting_options(CLI::App& cmd, LightingArgs& args) {
  cmd.add_option("--env", args.env,
                 "Environment: an equirectangular radiance map (.exr, .hdr; Blender's "
                 "orientation, +Y up), or none (unlit scenes are an error instead of white)");
  cmd.add_option("--env-color", args.env_color, "Environment: uniform radiance R,G,B");
  cmd.add_option("--env-strength", args.env_strength, "Multiplies the environment (and the sun)")
      ->capture_default_str();
  cmd.add_option("--env-rotate", args.env_rotate, "Turns the environment about +Y, in degrees")
      ->capture_default_str();
  cmd.add_option("--sky", args.sky,
                 "Environment: Preetham's clear sky and its sun, ELEVATION[,AZIMUTH[,TURBIDITY]] "
                 "in degrees (azimuth 0: the sun toward +Z, 90: toward +X; turbidity 1.7..10, "
                 "default 3)");
  cmd.add_option("--env-visible", args.env_visible,
                 "Whether pixels that see no surface show the environment (the lighting is the "
                 "same either way)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
}

LightingOptions lighting_options(const LightingArgs& args) {
  LightingOptions o;
  o.env = args.env;
  if (!args.env_color.empty()) o.env_color = parse_env_color(args.env_color, "--env-color");
  o.sky = args.sky;
  o.strength = args.env_strength;
  o.rotate_degrees = args.env_rotate;
  o.visible = args.env_visible != "off";
  return o;
}

nlohmann::json lights_json(const Scene& scene) {
  const LightSummary s = summarize_lights(scene);
  nlohmann::json j = {{"emissive_triangles", s.emissive_triangles},
                      {"emissive_materials", s.emissive_materials},
                      {"point", s.point},
                      {"spot", s.spot},
                      {"directional", s.directional},
                      {"suns", s.suns}};
  j["environment"] =
      s.environment.empty() ? nlohmann::json(nullptr) : nlohmann::json(s.environment);
  return j;
}

} // namespace irad::apps
