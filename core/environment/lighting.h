#pragma once
// Which lights a scene is rendered with (docs/environment.md): its own emitters and
// KHR_lights_punctual lights, plus at most one environment from the command line:
//   --env FILE        an equirectangular radiance map (.exr or .hdr,
//   core/environment/environment_file.h)
//   --env-color R,G,B a uniform environment
//   --sky E[,A[,T]]   Preetham's clear sky with its sun (core/environment/sky.h; the sun a
//   directional light)
// scaled by --env-strength and turned by --env-rotate degrees about +Y. A scene with no light of
// its own and none of these is lit by a uniform white environment of radiance 1, with one
// warning; `--env none` makes that an error instead (and adds no environment).
#include "core/scene/scene.h"
#include "core/util/log.h"

#include <glm/glm.hpp>
#include <optional>
#include <string>

namespace irad {

struct SkyOptions;

struct LightingOptions {
  std::string env;                    // FILE, "none", or empty
  std::optional<glm::vec3> env_color; // --env-color
  std::string sky;                    // --sky text, empty: none
  float strength = 1.0f;              // --env-strength
  float rotate_degrees = 0.0f;        // --env-rotate
  bool visible = true;                // --env-visible on|off
  int sky_width = 512;                // texels across the baked sky map
};

// Gives `scene` its environment (and the sky's sun) as the options say. Throws irad::Error naming
// the option (and the file) for a bad value or map, two environments at once, or a scene left
// without any light.
void light_scene(Scene& scene, const LightingOptions& options, Log& log);

// The light sources a scene is rendered with, for --stats.
struct LightSummary {
  std::size_t emissive_triangles = 0, emissive_materials = 0;
  std::size_t point = 0, spot = 0, directional = 0, suns = 0; // suns: directional with a disk
  std::string environment; // Environment::source(): the file, "uniform R,G,B", the sky; or empty
};
LightSummary summarize_lights(const Scene& scene);

} // namespace irad
