#pragma once
// The environment options every rendering subcommand shares (core/environment/lighting.h):
// --env FILE|none, --env-color R,G,B, --env-strength S, --env-rotate DEG,
// --sky ELEVATION[,AZIMUTH[,TURBIDITY]], --env-visible on|off.
#include "core/environment/lighting.h"

#include <nlohmann/json.hpp>
#include <string>

namespace CLI {
class App;
}

namespace irad::apps {

struct LightingArgs {
  std::string env, env_color, sky, env_visible = "on";
  float env_strength = 1.0f;
  float env_rotate = 0.0f;
};

void add_lighting_options(CLI::App& cmd, LightingArgs& args);
// Throws irad::Error naming the option for a value that does not parse.
LightingOptions lighting_options(const LightingArgs& args);
// The light sources of a lit scene as --stats writes them.
nlohmann::json lights_json(const Scene& scene);

} // namespace irad::apps
