// irad scene NAME -o OUT.gltf [--albedo R] [--radiance L] [--subdivisions K] [--scale S]: writes
// one of the analytic scenes of design.md section 3 (core/scene/analytic_scenes.h) as glTF and
// prints its answer on stdout:
//   scene <description>
//   triangles <count>
//   expected_radiance <value>          (integrating-sphere, furnace-box)
//   expected_radiance varies per pixel: ...   (square-light: Lambert's formula)
// Defaults: albedo 0.5, radiance 1 (the emitters' radiance), 4 sphere subdivisions, scale 1.
// --scale multiplies every length (sphere radius 1, box side 1; square light: side 1, height 1,
// plane side 6), so a scale-invariant estimator must give the same image at any S. Options that do
// not apply to the chosen scene (--subdivisions other than for the sphere) are errors.
#include "apps/commands.h"
#include "apps/options.h"
#include "core/gltf/writer.h"
#include "core/scene/analytic_scenes.h"
#include "core/util/error.h"

#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <numbers>
#include <string>

namespace irad::apps {

namespace {

struct SceneArgs {
  std::string name;
  std::string output;
  double albedo = 0.5;
  double radiance = 1.0;
  int subdivisions = kDefaultSphereSubdivisions;
  double scale = 1.0;
  CLI::Option* subdivisions_option = nullptr;
};

void check_args(const SceneArgs& args) {
  if (!(args.scale > 0.0 && std::isfinite(args.scale)))
    throw Error("", "--scale", fmt::format("{} is not a finite number > 0", args.scale));
  if (args.name != "integrating-sphere" && args.subdivisions_option->count() > 0)
    throw Error("", "--subdivisions", "applies to integrating-sphere only");
  const std::filesystem::path out(args.output);
  if (out.extension() != ".gltf")
    throw Error(args.output, "-o", "the scene is written as .gltf (JSON, embedded buffer)");
  require_writable(args.output, "-o");
}

// The scene and the line that states its answer.
std::pair<AnalyticScene, std::string> build(const SceneArgs& args) {
  const double s = args.scale;
  if (args.name == "integrating-sphere")
    return {integrating_sphere(s, args.albedo, args.subdivisions, args.radiance), ""};
  if (args.name == "furnace-box") return {furnace_box(s, args.albedo, args.radiance), ""};
  SquareLight light;
  light.side = s;
  light.height = s;
  light.plane_side = 6.0 * s;
  light.radiance = args.radiance;
  light.albedo = args.albedo;
  const std::string answer = fmt::format(
      "varies per pixel: the plane z = 0 shows albedo/pi * E(x) = {:.9g} * E(x), with E(x) the "
      "irradiance from the light square [{:g}, {:g}]^2 at height {:g} of radiance {:g} by "
      "Lambert's polygon formula (direct light only)",
      args.albedo / std::numbers::pi, -0.5 * s, 0.5 * s, s, args.radiance);
  return {square_light(light), answer};
}

int run_scene(const SceneArgs& args) {
  check_args(args);
  const auto [analytic, answer] = build(args);
  write_gltf(analytic.scene, args.output);
  fmt::print("scene {}\n", analytic.scene.source);
  fmt::print("triangles {}\n", analytic.scene.triangle_count());
  if (analytic.expected_radiance)
    fmt::print("expected_radiance {:.9g}\n", *analytic.expected_radiance);
  else
    fmt::print("expected_radiance {}\n", answer);
  std::fflush(stdout);
  return 0;
}

} // namespace

void add_scene_command(CLI::App& app, Commands& commands) {
  auto args = std::make_shared<SceneArgs>();
  CLI::App* cmd = app.add_subcommand(
      "scene", "Write an analytic scene (known answer) as glTF and print the answer");
  cmd->add_option("name", args->name, "integrating-sphere, furnace-box or square-light")
      ->required()
      ->check(CLI::IsMember({"integrating-sphere", "furnace-box", "square-light"}));
  cmd->add_option("-o,--output", args->output, "Output scene (.gltf)")->required();
  cmd->add_option("--albedo", args->albedo, "Albedo of the surfaces (the plane for square-light)")
      ->capture_default_str();
  cmd->add_option("--radiance", args->radiance, "Emitted radiance of the emitters")
      ->capture_default_str();
  args->subdivisions_option =
      cmd->add_option("--subdivisions", args->subdivisions,
                      "integrating-sphere: icosahedron subdivisions (20*4^K triangles)")
          ->capture_default_str();
  cmd->add_option("--scale", args->scale, "Multiplies every length")->capture_default_str();
  cmd->callback([args, &commands] { commands.selected = [args] { return run_scene(*args); }; });
}

} // namespace irad::apps
