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
  int shadow_res = 0;
  float clamp = 0.05f;
  std::string camera;
  float exposure = 0.0f;
  std::string tone_map = "clamp";
  std::string stats;
  bool quiet = false;
  std::string estimator = "raster";
  std::uint32_t spp = 64;
  std::uint64_t seed = 0;
  unsigned threads = 0;
  bool bias_compensation = false;
  std::uint32_t bias_samples = 16;
  std::string gl = "auto";
  std::string sequence = "halton";
  int interleave = 4;
  int gl_device = -1;
};

Estimator parse_estimator(const std::string& name) {
  if (name == "rt-vpl") return Estimator::RtVpl;
  if (name == "pt") return Estimator::Pt;
  return Estimator::Raster;
}

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
  nlohmann::json seconds = {{"load", r.seconds.load}, {"total", r.seconds.total}};
  if (args.estimator == "pt") {
    seconds["trace"] = r.seconds.trace;
    return {{"scene", args.scene},
            {"estimator", args.estimator},
            {"spp", args.spp},
            {"seed", args.seed},
            {"size", {r.view.width, r.view.height}},
            {"triangles", r.scene.triangle_count()},
            {"camera", r.camera.name},
            {"seconds", seconds}};
  }
  seconds["walk"] = r.seconds.walk;
  if (args.bias_compensation) seconds["compensation"] = r.seconds.compensation;
  if (args.estimator == "raster") {
    seconds["raster"] = r.seconds.raster;
    seconds["readback"] = r.seconds.readback;
  } else {
    seconds["trace"] = r.seconds.trace;
  }
  return {{"scene", args.scene},
          {"estimator", args.estimator},
          {"vpls", r.vpls.vpls.size()},
          {"vpls_planned", r.vpls.planned},
          {"passes", r.passes},
          {"paths", r.vpls.paths},
          {"sequence", args.sequence},
          {"rho_bar", r.vpls.rho_bar},
          {"l_max", r.vpls.l_max},
          {"depth_capped", r.vpls.depth_capped},
          {"size", {r.view.width, r.view.height}},
          {"triangles", r.scene.triangle_count()},
          {"shadow_res", shadow_resolution_for(args.shadow_res, r.view)},
          {"interleave", args.interleave},
          {"clamp", args.clamp},
          {"clamp_distance", args.clamp * r.scene.bounds.diagonal()},
          {"camera", r.camera.name},
          {"gl", r.gl},
          {"clamped_fraction", r.clamped_fraction},
          {"bias_compensation", args.bias_compensation},
          {"seconds", seconds}};
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

void print_summary(const RenderArgs& args, const RenderResult& r) {
  if (args.estimator == "pt") {
    std::fprintf(stderr, "irad: %s: %dx%d, pt %u spp in %.2f s (load %.2f, trace %.2f)\n",
                 args.scene.c_str(), r.view.width, r.view.height, args.spp, r.seconds.total,
                 r.seconds.load, r.seconds.trace);
    return;
  }
  const double stage = args.estimator == "raster" ? r.seconds.raster : r.seconds.trace;
  std::fprintf(stderr,
               "irad: %s: %dx%d, %s, %u paths, %zu VPLs (l_max %d, rho_bar %.4f) in %.2f s "
               "(load %.2f, walk %.2f, %s %.2f)\n",
               args.scene.c_str(), r.view.width, r.view.height, args.estimator.c_str(),
               r.vpls.paths, r.vpls.vpls.size(), r.vpls.l_max, r.vpls.rho_bar, r.seconds.total,
               r.seconds.load, r.seconds.walk, args.estimator == "raster" ? "raster" : "trace",
               stage);
}

int run_render(const RenderArgs& args) {
  Log log;
  log.set_quiet(args.quiet);
  RenderRequest request;
  request.scene_path = args.scene;
  if (!args.size.empty()) request.size = parse_size(args.size);
  request.camera = args.camera;
  request.walk.paths = args.paths;
  request.walk.sequence = parse_sequence(args.sequence);
  request.walk.seed = args.seed;
  request.raster.shadow_resolution = args.shadow_res;
  request.raster.clamp = args.clamp;
  request.raster.backend = args.gl == "egl"      ? GlBackend::Egl
                           : args.gl == "osmesa" ? GlBackend::OsMesa
                                                 : GlBackend::Auto;
  request.raster.gl_device = args.gl_device;
  request.raster.interleave = args.interleave;
  request.progress = !args.quiet && isatty(STDERR_FILENO);
  request.estimator = parse_estimator(args.estimator);
  request.pt.spp = args.spp;
  request.pt.seed = args.seed;
  request.pt.threads = args.threads;
  request.bias_compensation = args.bias_compensation;
  request.bias_samples = args.bias_samples;
  request.clamped_fraction = !args.stats.empty();
  if (args.paths == 0) throw Error("", "--paths", "must be at least 1");
  if (args.spp == 0) throw Error("", "--spp", "must be at least 1");
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
  if (!args.quiet) print_summary(args, r);
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
  cmd->add_option("--shadow-res", args->shadow_res,
                  "Shadow cube face resolution (0: a quarter of the image side, 64..1024)")
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
  cmd->add_option("--estimator", args->estimator,
                  "raster: instant radiosity on the GPU (OpenGL); rt-vpl: the same VPLs with "
                  "ray-traced visibility; pt: path-traced reference")
      ->check(CLI::IsMember({"raster", "rt-vpl", "pt"}))
      ->capture_default_str();
  cmd->add_option("--sequence", args->sequence,
                  "Points of the walk: halton (the seed's), scrambled-halton or random (seeded)")
      ->check(CLI::IsMember({"halton", "scrambled-halton", "random"}))
      ->capture_default_str();
  cmd->add_option("--spp", args->spp, "pt: samples per pixel")->capture_default_str();
  cmd->add_option("--seed", args->seed, "Random seed (pt, scrambled-halton, random)")
      ->capture_default_str();
  cmd->add_option("--threads", args->threads, "pt, rt-vpl: CPU threads (0: all cores)")
      ->capture_default_str();
  cmd->add_flag("--bias-compensation", args->bias_compensation,
                "raster, rt-vpl: add back what the clamp removes (short ray-traced gather paths)");
  cmd->add_option("--bias-samples", args->bias_samples,
                  "gather directions per pixel for --bias-compensation")
      ->capture_default_str();
  cmd->add_option(
         "--interleave", args->interleave,
         "Raster: k > 1 splits the VPLs into k x k sets, each pixel of a k x k tile lit by "
         "one set, then a geometry-aware filter (1: every VPL shades every pixel)")
      ->capture_default_str();
  cmd->add_option("--gl", args->gl,
                  "OpenGL for the raster: auto (a GPU through EGL if there is one, else OSMesa), "
                  "egl (a device, or Mesa's surfaceless platform), osmesa")
      ->check(CLI::IsMember({"auto", "egl", "osmesa"}))
      ->capture_default_str();
  cmd->add_option("--gl-device", args->gl_device, "EGL device index (implies EGL)");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress, warnings or summary on stderr");
  cmd->callback([args, &commands] { commands.selected = [args] { return run_render(*args); }; });
}

} // namespace irad::apps
