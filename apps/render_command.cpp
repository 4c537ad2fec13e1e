// irad render SCENE -o OUT.exr [-o OUT.png] ...: one instant radiosity image.
#include "apps/commands.h"
#include "apps/render_pipeline.h"
#include "core/error.h"
#include "core/image_io.h"

#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <unistd.h>

namespace irad::apps {

namespace {

struct RenderArgs {
  std::string scene;
  std::vector<std::string> outputs;
  std::string size;
  std::uint32_t paths = 256;
  int shadow_res = 256;
  float clamp = 0.05f;
  std::string camera;
  float exposure = 0.0f;
  std::string tone_map = "clamp";
  std::string stats;
  bool quiet = false;
};

std::pair<int, int> parse_size(const std::string& text) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X'))
    throw Error("", "--size", fmt::format("'{}' is not WIDTHxHEIGHT", text));
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    throw Error("", "--size", fmt::format("{}x{} is out of range (1..16384 per side)", w, h));
  return {w, h};
}

// Every output must be writable before any work starts: known type, existing folder.
void check_folder(const std::string& path, const char* option) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw Error(path, option, fmt::format("output folder '{}' does not exist", parent.string()));
}

nlohmann::json stats_json(const RenderArgs& args, const RenderResult& r) {
  return {{"scene", args.scene},
          {"vpls", r.vpls.vpls.size()},
          {"vpls_planned", r.vpls.planned},
          {"passes", r.passes},
          {"paths", r.vpls.paths},
          {"rho_bar", r.vpls.rho_bar},
          {"l_max", r.vpls.l_max},
          {"depth_capped", r.vpls.depth_capped},
          {"size", {r.view.width, r.view.height}},
          {"triangles", r.scene.triangle_count()},
          {"shadow_res", args.shadow_res},
          {"clamp", args.clamp},
          {"clamp_distance", args.clamp * r.scene.bounds.diagonal()},
          {"camera", r.camera.name},
          {"gl", r.gl},
          {"seconds",
           {{"load", r.seconds.load},
            {"walk", r.seconds.walk},
            {"raster", r.seconds.raster},
            {"readback", r.seconds.readback},
            {"total", r.seconds.total}}}};
}

void write_stats(const std::string& path, const nlohmann::json& stats) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << stats.dump(2) << '\n';
    if (!out) throw Error(path, "--stats", "cannot write");
  }
  std::filesystem::rename(tmp, path);
}

int run_render(const RenderArgs& args) {
  Log log;
  log.set_quiet(args.quiet);
  RenderRequest request;
  request.scene_path = args.scene;
  if (!args.size.empty()) request.size = parse_size(args.size);
  request.camera = args.camera;
  request.walk.paths = args.paths;
  request.raster.shadow_resolution = args.shadow_res;
  request.raster.clamp = args.clamp;
  request.progress = !args.quiet && isatty(STDERR_FILENO);
  if (args.paths == 0) throw Error("", "--paths", "must be at least 1");
  for (const std::string& o : args.outputs) {
    image_format_of(o);
    check_folder(o, "-o");
  }
  if (!args.stats.empty()) check_folder(args.stats, "--stats");

  const RenderResult r = render_scene(request, log);
  PngOptions png;
  png.exposure = args.exposure;
  png.tone_map = args.tone_map == "reinhard" ? ToneMap::Reinhard : ToneMap::Clamp;
  for (const std::string& o : args.outputs) write_image(o, r.image, png);
  if (!args.stats.empty()) write_stats(args.stats, stats_json(args, r));
  if (!args.quiet)
    std::fprintf(stderr,
                 "irad: %s: %dx%d, %u paths, %zu VPLs (l_max %d, rho_bar %.4f) in %.2f s "
                 "(load %.2f, walk %.2f, raster %.2f)\n",
                 args.scene.c_str(), r.view.width, r.view.height, r.vpls.paths, r.vpls.vpls.size(),
                 r.vpls.l_max, r.vpls.rho_bar, r.seconds.total, r.seconds.load, r.seconds.walk,
                 r.seconds.raster);
  return 0;
}

} // namespace

void add_render_command(CLI::App& app, Commands& commands) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render one image of a glTF scene");
  cmd->add_option("scene", args->scene, "glTF 2.0 scene (.gltf or .glb)")->required();
  cmd->add_option("-o,--output", args->outputs,
                  "Output image (.exr linear float, .png sRGB); "
                  "may be given several times")
      ->required();
  cmd->add_option("--size", args->size,
                  "Image size WIDTHxHEIGHT (default: 512 high, camera aspect)");
  cmd->add_option("--paths", args->paths, "Number of light paths N")->capture_default_str();
  cmd->add_option("--shadow-res", args->shadow_res, "Shadow cube face resolution")
      ->capture_default_str();
  cmd->add_option("--clamp", args->clamp,
                  "Clamp distance d_min as a fraction of the scene's bounding diagonal")
      ->capture_default_str();
  cmd->add_option("--camera", args->camera, "Camera name or index (default: the first)");
  cmd->add_option("--exposure", args->exposure, "PNG exposure in stops (EV)")
      ->capture_default_str();
  cmd->add_option("--tonemap", args->tone_map, "PNG tone map")
      ->check(CLI::IsMember({"clamp", "reinhard"}))
      ->capture_default_str();
  cmd->add_option("--stats", args->stats, "Write statistics as JSON to this file");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress, warnings or summary on stderr");
  cmd->callback([args, &commands] { commands.selected = [args] { return run_render(*args); }; });
}

} // namespace irad::apps
