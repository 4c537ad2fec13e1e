#include "core/environment/lighting.h"

#include "core/environment/environment_file.h"
#include "core/environment/sky.h"
#include "core/util/error.h"

#include <cmath>
#include <fmt/format.h>
#include <memory>
#include <numbers>
#include <set>

namespace irad {

namespace {

float radians(float degrees) {
  return degrees * std::numbers::pi_v<float> / 180.0f;
}

bool has_own_light(const Scene& scene) {
  return scene.has_emitters() || !scene.lights.empty();
}

// The options that name an environment, for the "only one" error.
std::vector<std::string> chosen(const LightingOptions& o) {
  std::vector<std::string> c;
  if (!o.env.empty() && o.env != "none") c.push_back("--env");
  if (o.env_color) c.push_back("--env-color");
  if (!o.sky.empty()) c.push_back("--sky");
  return c;
}

void check_values(const LightingOptions& o) {
  if (!std::isfinite(o.strength) || o.strength < 0.0f)
    throw Error("", "--env-strength",
                fmt::format("must be a finite number >= 0, got {}", o.strength));
  if (!std::isfinite(o.rotate_degrees))
    throw Error("", "--env-rotate", "must be a finite number of degrees");
  const std::vector<std::string> c = chosen(o);
  if (c.size() > 1)
    throw Error("", c[1],
                fmt::format("cannot be combined with {}: one environment at a time", c[0]));
  if (o.env == "none" && (o.env_color || !o.sky.empty()))
    throw Error("", o.env_color ? "--env-color" : "--sky", "cannot be combined with --env none");
}

std::shared_ptr<Environment> make_environment(Image map, const LightingOptions& o,
                                              std::string source) {
  auto env = std::make_shared<Environment>(std::move(map), o.strength, radians(o.rotate_degrees),
                                           std::move(source));
  env->visible = o.visible;
  return env;
}

// --sky: the baked map and, above the horizon, the sun (strength applied to both).
void add_sky(Scene& scene, const LightingOptions& o, Log& log) {
  const SkyOptions sky = parse_sky(o.sky, "--sky");
  scene.environment =
      make_environment(preetham_sky_map(sky, o.sky_width), o,
                       fmt::format("Preetham sky (elevation {}, azimuth {}, turbidity {})",
                                   sky.elevation_deg, sky.azimuth_deg, sky.turbidity));
  if (std::optional<PunctualLight> sun = preetham_sun(sky)) {
    sun->intensity *= o.strength;
    // The sun turns with the map (--env-rotate), as its sky does.
    sun->direction = glm::normalize(scene.environment->to_world(sun->direction));
    scene.lights.push_back(*sun);
  } else {
    log.warn(fmt::format("--sky: the sun is at or below the horizon (elevation {}): the clear-sky "
                         "model has no twilight, so the sky and the sun are black",
                         sky.elevation_deg));
  }
}

} // namespace

void light_scene(Scene& scene, const LightingOptions& o, Log& log) {
  check_values(o);
  if (!o.env.empty() && o.env != "none") {
    scene.environment = make_environment(read_environment_map(o.env, "--env"), o, o.env);
  } else if (o.env_color) {
    const glm::vec3 c = *o.env_color;
    scene.environment = make_environment(Environment::uniform_map(c), o,
                                         fmt::format("uniform {},{},{}", c.x, c.y, c.z));
  } else if (!o.sky.empty()) {
    add_sky(scene, o, log);
  } else if (!has_own_light(scene) && o.env != "none") {
    log.warn(scene.source + ": the scene has no light of its own (no emissive material, no "
                            "KHR_lights_punctual light): lit by a uniform white environment of "
                            "radiance 1 (--env none refuses such scenes)");
    scene.environment =
        make_environment(Environment::uniform_map(glm::vec3(1.0f)), o, "uniform 1,1,1 (default)");
  }
  if (!has_own_light(scene) && !scene.has_environment())
    throw Error(scene.source, o.env == "none" ? "--env none" : "",
                "no light: no emissive material, no KHR_lights_punctual light and no "
                "environment that carries light");
}

LightSummary summarize_lights(const Scene& scene) {
  LightSummary s;
  std::set<std::uint32_t> materials;
  for (std::size_t t = 0; t < scene.triangle_count(); ++t)
    if (scene.material_of(t).emissive() && triangle_area(scene, t) > 0.0f) {
      ++s.emissive_triangles;
      materials.insert(scene.triangle_material[t]);
    }
  s.emissive_materials = materials.size();
  for (const PunctualLight& l : scene.lights) {
    if (l.kind == PunctualLight::Kind::Point) ++s.point;
    if (l.kind == PunctualLight::Kind::Spot) ++s.spot;
    if (l.kind == PunctualLight::Kind::Directional) ++s.directional;
    if (l.angular_radius > 0.0f) ++s.suns;
  }
  if (scene.environment) s.environment = scene.environment->source();
  return s;
}

} // namespace irad
