// irad render SCENE -o OUT.exr [-o OUT.png] ...: one instant radiosity image.
// SIGINT and SIGTERM stop the render early and write nothing (each output is written whole or
// not at all: through a .tmp and a rename); with --partial the image accumulated so far goes to
// OUT.partial.EXT instead. Then the process ends by the signal. A second signal ends it at once.
#include "apps/commands.h"
#include "apps/lighting_options.h"
#include "apps/options.h"
#include "apps/progress_line.h"
#include "apps/render_parts.h"
#include "core/image/image_io.h"
#include "core/util/error.h"
#include "core/util/freed_memory.h"
#include "irad/render.h"

#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <unistd.h>

namespace irad::apps {

namespace {

struct RenderArgs {
  std::string scene;
  std::vector<std::string> outputs;
  std::string size;
  std::string paths = "auto"; // N, or auto: the light budget (core/lights/light_budget.h)
  int shadow_res = 0;
  float clamp = 0.05f;
  std::string clamp_mode = "local";
  int clamp_neighbours = 8;
  std::optional<float> clamp_scale; // default: RenderOptions' (0.5, 1.0 with clusters)
  std::string clusters = "auto";    // C (0: every VPL), or auto: the light budget
  std::size_t cluster_rows = 256;
  std::uint32_t rounds = 1;
  std::string camera;
  std::string gltf_scene;
  LookAtArgs look;
  std::optional<float> time;
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
  float traced_roughness = RenderOptions{}.traced_roughness;
  std::uint32_t glossy_samples = RenderOptions{}.glossy_samples;
  std::string compensation = "screen";
  std::string gl = "auto";
  std::string sequence = "halton";
  std::string light_allocation = "power";
  std::string interleave = "auto"; // k, or auto (lib/render.cpp)
  int batch = RasterOptions{}.batch;
  std::string shadow_lod = "on";
  std::string shadow_occlusion = "on";
  std::string hierarchy_cache = "on";
  std::string shadow_helpers = "auto";
  std::string shadow_planes = "auto";
  std::string visibility = "auto";
  std::string camera_lod = "off";
  std::string jitter = "off";
  std::string interleave_edges = "auto";
  int gl_device = -1;
  bool partial = false;
  std::uint64_t max_triangles = LoadLimits{}.max_triangles;
  std::uint64_t max_file_mib = LoadLimits{}.max_file_bytes >> 20;
  int max_texture_size = LoadLimits{}.max_texture_size;
  LightingArgs lighting;
  PartArgs part; // --path-range, --spp-range
};

// Set by SIGINT or SIGTERM during a render (lock-free, so async-signal-safe).
std::atomic<bool> g_interrupted{false};
volatile std::sig_atomic_t g_signal = 0;
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void on_interrupt(int signal) {
  g_signal = signal;
  g_interrupted.store(true);
}

// Installs on_interrupt for SIGINT and SIGTERM for its lifetime; the handler resets itself, so a
// second signal takes the default action (the process ends at once).
class InterruptHandler {
public:
  InterruptHandler() {
    struct sigaction action = {};
    action.sa_handler = &on_interrupt;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESETHAND;
    sigaction(SIGINT, &action, &old_int_);
    sigaction(SIGTERM, &action, &old_term_);
  }
  ~InterruptHandler() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;

private:
  struct sigaction old_int_ = {};
  struct sigaction old_term_ = {};
};

// OUT.partial.EXT for OUT.EXT.
std::string partial_name(const std::string& output) {
  std::filesystem::path p(output);
  const std::string extension = p.extension().string();
  p.replace_extension(".partial" + extension);
  return p.string();
}

// Ends the process by `signal` with its default action, as if irad had not caught it.
[[noreturn]] void die_by(int signal) {
  std::fflush(stdout);
  std::fflush(stderr);
  std::signal(signal, SIG_DFL);
  std::raise(signal);
  std::_Exit(128 + signal); // not reached for SIGINT and SIGTERM
}

nlohmann::json stats_json(const RenderArgs& args, const Scene& scene, const RenderResult& r) {
  nlohmann::json seconds = {{"load", r.seconds.load}, {"total", r.seconds.total}};
  if (args.estimator == "pt") {
    seconds["trace"] = r.seconds.trace;
    return {{"scene", args.scene},
            {"estimator", args.estimator},
            {"spp", args.spp},
            {"seed", args.seed},
            {"size", {r.view.width, r.view.height}},
            {"triangles", scene.triangle_count()},
            {"camera", r.camera.name},
            {"lights", lights_json(scene)},
            {"heap_huge_pages", heap_huge_pages()},
            {"seconds", seconds}};
  }
  seconds["walk"] = r.seconds.walk;
  seconds["statistics"] = r.seconds.statistics; // not in total
  if (r.clusters > 0) seconds["cluster"] = r.seconds.cluster;
  if (args.bias_compensation || args.compensation != "off")
    seconds["compensation"] = r.seconds.compensation;
  const bool glossy_pass = args.traced_roughness > 0.0f && !scene.all_lambertian();
  if (glossy_pass) seconds["glossy"] = r.seconds.glossy;
  if (args.estimator == "raster") {
    seconds["raster"] = r.seconds.raster;
    seconds["readback"] = r.seconds.readback;
    if (r.visibility == "rays") seconds["visibility"] = r.seconds.visibility; // part of raster
    // In the order the stages ran: [[name, seconds], ...].
    const auto stages = [](const std::vector<std::pair<std::string, double>>& list) {
      nlohmann::json out = nlohmann::json::array();
      for (const auto& [stage, t] : list) out.push_back({stage, t});
      return out;
    };
    seconds["raster_setup"] = stages(r.seconds.raster_setup);
    if (!r.seconds.hierarchy_beside.empty())
      seconds["hierarchy_beside"] = stages(r.seconds.hierarchy_beside);
    if (scene.has_specular()) seconds["mirrors"] = r.seconds.trace; // walk/estimators/mirror_pass.h
  } else {
    seconds["trace"] = r.seconds.trace;
  }
  return {
      {"scene", args.scene},
      {"estimator", args.estimator},
      {"vpls", r.vpls.vpls.size()},
      {"vpls_planned", r.vpls.planned},
      {"passes", r.passes},
      {"single_passes", r.single_passes},
      {"shadow_triangles", r.shadow_triangles},
      {"shadow_levels",
       {{"built", r.shadow_levels.built},
        {"read", r.shadow_levels.read},
        {"seconds", r.shadow_levels.seconds}}},
      {"edge_pixels", r.edge_pixels},
      {"unsure_pixels", r.unsure_pixels},
      {"paths", r.vpls.paths},
      {"sequence", args.sequence},
      {"light_allocation", args.light_allocation},
      {"rho_bar", r.vpls.rho_bar},
      {"l_max", r.vpls.l_max},
      {"depth_capped", r.vpls.depth_capped},
      {"size", {r.view.width, r.view.height}},
      {"triangles", scene.triangle_count()},
      {"shadow_res", r.shadow_resolution}, // as drawn: 0 for rt-vpl
      {"interleave", r.interleave},        // as drawn: auto resolved
      {"interleave_edges", r.edge_mode},   // as drawn: auto resolved
      {"batch", args.batch},
      {"shadow_lod", args.shadow_lod},
      {"shadow_occlusion", args.shadow_occlusion == "on"},
      {"shadow_helpers", r.shadow_helpers}, // as drawn: auto resolved, 0 when none were made
      {"hierarchy_cache", {{"outcome", r.hierarchy_cache}, {"reason", r.hierarchy_cache_reason}}},
      {"camera_hierarchy_cache",
       {{"outcome", r.camera_hierarchy_cache}, {"reason", r.camera_hierarchy_cache_reason}}},
      {"camera_triangles", r.camera_triangles},
      {"gpu_bytes",
       {{"scene", r.gpu_bytes.scene},
        {"shadow_pages", r.gpu_bytes.shadow_pages},
        {"camera_pages", r.gpu_bytes.camera_pages}}},
      {"wall_cache", {{"outcome", r.wall_cache}, {"reason", r.wall_cache_reason}}},
      {"shadow_planes", r.shadow_planes}, // as drawn: auto resolved
      {"visibility", r.visibility},       // raster, as drawn: auto resolved
      {"thinnest_wall", r.thinnest_wall},
      {"heap_huge_pages", heap_huge_pages()}, // apps/main.cpp
      {"jitter", args.jitter == "on"},
      {"clamp", args.clamp},
      {"clamp_distance", args.clamp * scene.bounds.diagonal()}, // local: the cap
      {"clamp_mode", args.clamp_mode},
      {"clusters", r.clusters}, // as drawn: auto resolved
      {"rounds", r.rounds},
      {"cluster_rows", args.cluster_rows},
      {"walk_vpls", r.walk_vpls},
      {"cluster_dropped", r.cluster_dropped},
      {"camera", r.camera.name},
      {"gl", r.gl},
      {"clamped_fraction", r.clamped_fraction},
      {"bias_compensation", args.bias_compensation},
      {"compensation", args.bias_compensation ? "traced" : args.compensation},
      {"compensation_fallback", r.compensation_fallback},
      {"traced_roughness", glossy_pass ? args.traced_roughness : 0.0f},
      {"glossy_samples", args.glossy_samples},
      {"glossy_pixels", r.glossy_pixels},
      {"glossy_rays", r.glossy_rays},
      {"glossy_on_screen", r.glossy_on_screen},
      {"glossy_exact", r.glossy_exact},
      {"lights", lights_json(scene)},
      {"seconds", seconds}};
}

// Written as image_io writes images: into PATH.tmp, renamed over PATH; the .tmp never stays.
void write_stats(const std::string& path, const nlohmann::json& stats) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::exists(status) && !fs::is_regular_file(status))
    throw Error(path, "--stats", "cannot write: it exists and is not a regular file");
  // Invalid UTF-8 (in a file name) is replaced rather than thrown midway.
  const std::string text =
      stats.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
  const std::string tmp = path + ".tmp";
  std::string reason;
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (out) out << text;
    if (out) out.close();
    if (!out) reason = errno != 0 ? std::generic_category().message(errno) : "I/O error";
  }
  if (reason.empty()) {
    fs::rename(tmp, path, ec);
    if (!ec) return;
    reason = ec.message();
  }
  if (fs::is_regular_file(fs::symlink_status(tmp, ec))) fs::remove(tmp, ec);
  throw Error(path, "--stats", "cannot write: " + reason);
}

void print_summary(const RenderArgs& args, const Scene& scene, const RenderResult& r) {
  if (args.estimator == "pt") {
    std::fprintf(stderr, "irad: %s: %dx%d, pt %u spp in %.2f s (load %.2f, trace %.2f)\n",
                 args.scene.c_str(), r.view.width, r.view.height, args.spp, r.seconds.total,
                 r.seconds.load, r.seconds.trace);
    return;
  }
  const double stage = args.estimator == "raster" ? r.seconds.raster : r.seconds.trace;
  std::fprintf(
      stderr,
      "irad: %s: %dx%d, %s, %u paths, %zu VPLs (l_max %d, rho_bar %.4f) in %.2f s "
      "(load %.2f, walk %.2f%s, %s %.2f%s)\n",
      args.scene.c_str(), r.view.width, r.view.height, args.estimator.c_str(), r.vpls.paths,
      r.vpls.vpls.size(), r.vpls.l_max, r.vpls.rho_bar, r.seconds.total, r.seconds.load,
      r.seconds.walk,
      r.clusters > 0
          ? fmt::format(", clusters of {} VPLs {:.2f}", r.walk_vpls, r.seconds.cluster).c_str()
          : "",
      args.estimator == "raster" ? "raster" : "trace", stage,
      args.estimator == "raster" && scene.has_specular()
          ? fmt::format(", mirrors {:.2f}", r.seconds.trace).c_str()
          : "");
}

int run_render(const RenderArgs& args) {
  Log log;
  log.set_quiet(args.quiet);
  RenderRequest request;
  request.scene_path = args.scene;
  if (!args.size.empty()) request.render.size = parse_size_option(args.size);
  request.render.camera = args.camera;
  request.scene.gltf_scene = args.gltf_scene;
  request.scene.own_camera = parse_look_at(args.look, args.camera);
  request.scene.time = args.time;
  const auto paths = parse_count_or_auto(args.paths, "--paths", 1, 1u << 30);
  request.render.auto_paths = !paths;
  request.render.walk.paths = static_cast<std::uint32_t>(paths.value_or(256));
  request.render.walk.sequence = parse_sequence(args.sequence);
  request.render.walk.seed = args.seed;
  request.render.walk.allocation =
      parse_light_allocation(args.light_allocation, "--light-allocation");
  request.render.raster.shadow_resolution = args.shadow_res;
  request.render.raster.clamp = args.clamp;
  request.render.local_clamp = args.clamp_mode == "local";
  request.render.clamp_neighbours = args.clamp_neighbours;
  if (args.clamp_scale)
    request.render.clamp_scale = request.render.cluster_clamp_scale = *args.clamp_scale;
  const auto clusters = parse_count_or_auto(args.clusters, "--clusters", 0, 1u << 24);
  request.render.auto_clusters = !clusters;
  request.render.clusters = clusters.value_or(0);
  request.render.cluster_rows = args.cluster_rows;
  request.render.rounds = args.rounds;
  request.render.raster.backend = parse_backend(args.gl);
  request.render.raster.gl_device = args.gl_device;
  // 0: automatic (RenderOptions::raster.interleave, lib/irad/render.h)
  request.render.raster.interleave =
      static_cast<int>(parse_count_or_auto(args.interleave, "--interleave", 1, 16).value_or(0));
  request.render.raster.batch = args.batch;
  request.render.raster.shadow_lod.mode = parse_shadow_lod(args.shadow_lod);
  request.render.raster.shadow_lod.occlusion = args.shadow_occlusion == "on";
  if (args.hierarchy_cache == "off") request.render.raster.hierarchy_cache.clear();
  if (args.shadow_helpers != "auto")
    request.render.raster.shadow_helpers = std::stoi(args.shadow_helpers);
  request.render.raster.shadow_lod.planes = parse_shadow_planes(args.shadow_planes);
  request.render.raster.visibility = parse_visibility(args.visibility);
  request.render.raster.camera_lod = parse_camera_lod(args.camera_lod);
  request.render.raster.jitter = args.jitter == "on";
  set_edge_pixels(args.interleave_edges, request.render); // checked by CLI11
  request.render.pt.pixel_footprint =
      args.jitter == "on"; // pt: each sample at a uniform pixel point
  request.render.estimator = parse_estimator(args.estimator);
  request.render.pt.spp = args.spp;
  request.render.pt.seed = args.seed;
  request.render.pt.threads = args.threads;
  request.render.bias_compensation = args.bias_compensation || args.compensation == "traced";
  request.render.screen_compensation = args.compensation == "screen";
  request.render.bias_samples = args.bias_samples;
  request.render.traced_roughness = args.traced_roughness;
  request.render.glossy_samples = args.glossy_samples;
  request.render.clamped_fraction = !args.stats.empty();
  request.scene.limits.max_triangles = args.max_triangles;
  request.scene.limits.max_file_bytes = args.max_file_mib << 20;
  request.scene.limits.max_texture_size = args.max_texture_size;
  request.scene.lighting = lighting_options(args.lighting);
  if (args.max_triangles < 1) throw Error("", "--max-triangles", "must be at least 1");
  if (args.max_file_mib < 1 || args.max_file_mib > 4095)
    throw Error("", "--max-file-size", "must lie in [1, 4095] MiB");
  if (args.max_texture_size < 1) throw Error("", "--max-texture-size", "must be at least 1");
  if (args.spp == 0) throw Error("", "--spp", "must be at least 1");
  for (const std::string& o : args.outputs) {
    image_format_of(o);
    require_writable(o, "-o");
  }
  if (!args.stats.empty()) require_writable(args.stats, "--stats");
  apply_part_ranges(args.part, request);

  const InterruptHandler interrupt_handler;
  request.render.cancel = &g_interrupted;
  const FileRender f = [&] {
    ProgressLine progress(!args.quiet && isatty(STDERR_FILENO)); // erased when the render ends
    if (progress.enabled()) request.render.progress = std::ref(progress);
    return render_file(request, log);
  }();
  const RenderResult& r = f.result;
  PngOptions png;
  png.exposure = args.exposure;
  png.tone_map = args.tone_map == "reinhard" ? ToneMap::Reinhard : ToneMap::Clamp;
  if (r.cancelled) {
    const int signal = g_signal;
    const char* name = signal == SIGTERM ? "SIGTERM" : "SIGINT";
    std::string written;
    if (args.partial && r.image.width() > 0) {
      for (const std::string& o : args.outputs) {
        write_image(partial_name(o), r.image, png);
        written += (written.empty() ? "" : ", ") + partial_name(o);
      }
    }
    std::fprintf(stderr, "irad: %s: interrupted by %s; %s\n", args.scene.c_str(), name,
                 written.empty() ? "nothing written" : ("partial image in " + written).c_str());
    die_by(signal);
  }
  const ExrAttributes header =
      is_part(args.part) ? part_header(args.part, request, r) : ExrAttributes{};
  for (const std::string& o : args.outputs) {
    if (image_format_of(o) == ImageFormat::Exr)
      write_exr(o, r.image, header);
    else
      write_image(o, r.image, png);
  }
  if (!args.stats.empty()) write_stats(args.stats, stats_json(args, f.scene, r));
  if (!args.quiet) print_summary(args, f.scene, r);
  // A signal after the image was complete: the outputs are whole; end as the signal asks.
  if (g_interrupted.load()) die_by(g_signal);
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
  cmd->add_option("--paths", args->paths,
                  "Number of light paths N, or auto: N from a pilot walk, so that the walk leaves "
                  "about 32768 VPLs (256..65536 paths)")
      ->capture_default_str();
  cmd->add_option("--shadow-res", args->shadow_res,
                  "Shadow cube face resolution (0: a quarter of the image side, 64..1024; "
                  "cluster representatives with --rounds 4 or more and the unsure pixels not "
                  "traced: at least half the side up to 128)")
      ->capture_default_str();
  cmd->add_option("--clamp", args->clamp,
                  "Clamp distance d_min as a fraction of the scene's bounding diagonal (local: "
                  "the largest d_min)")
      ->capture_default_str();
  cmd->add_option("--clamp-mode", args->clamp_mode,
                  "local: d_min follows the VPLs' spacing (--clamp-scale times the distance to "
                  "the --clamp-neighbours-th nearest VPL); global: --clamp everywhere")
      ->check(CLI::IsMember({"local", "global"}))
      ->capture_default_str();
  cmd->add_option("--clamp-neighbours", args->clamp_neighbours, "local clamp: k")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_option("--clamp-scale", args->clamp_scale,
                  "local clamp: d_min / r_k (default 0.5; 1.0 for cluster representatives)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--clusters", args->clusters,
                  "Draw the VPLs as at most this many cluster representatives (matrix "
                  "row-column sampling; 0: every VPL; auto: one per 16 VPLs, 256..2048, when the "
                  "walk leaves more than 4096 VPLs, else every VPL)")
      ->capture_default_str();
  cmd->add_option("--rounds", args->rounds,
                  "raster, rt-vpl: the mean of M renders of independent light sets (scrambled "
                  "Halton walks; the error falls as 1/M, as pt's with its samples)")
      ->check(CLI::Range(1u, 4096u))
      ->capture_default_str();
  cmd->add_option("--cluster-rows", args->cluster_rows,
                  "clusters: pixels whose rows are computed exactly")
      ->check(CLI::Range(std::size_t{1}, std::size_t{65536}))
      ->capture_default_str();
  cmd->add_option("--camera", args->camera, "Camera name or index (default: the first)");
  cmd->add_option("--scene", args->gltf_scene,
                  "glTF scene name or index (default: the file's default scene)");
  add_look_at_options(*cmd, args->look);
  add_lighting_options(*cmd, args->lighting);
  add_part_options(*cmd, args->part);
  cmd->add_option("--time", args->time, "Pose the glTF animation at T seconds (default: rest)");
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
  // Advanced (not in --help): the seed's one-light-after-the-other allocation, for measurements.
  cmd->add_option("--light-allocation", args->light_allocation,
                  "Share of the paths per light: power (design.md 6.2) or uniform")
      ->check(CLI::IsMember({"power", "uniform"}))
      ->group("");
  cmd->add_option("--spp", args->spp, "pt: samples per pixel")->capture_default_str();
  cmd->add_option("--seed", args->seed, "Random seed (pt, scrambled-halton, random)")
      ->capture_default_str();
  cmd->add_option("--threads", args->threads, "pt, rt-vpl: CPU threads (0: all cores)")
      ->capture_default_str();
  cmd->add_option("--compensation", args->compensation,
                  "raster, rt-vpl: add back what the clamp removes; screen: from the image where "
                  "the camera sees the gather hits; traced: ray-traced gather paths")
      ->check(CLI::IsMember({"off", "screen", "traced"}))
      ->capture_default_str();
  cmd->add_flag("--bias-compensation", args->bias_compensation,
                "raster, rt-vpl: add back what the clamp removes (short ray-traced gather paths)");
  cmd->add_option("--bias-samples", args->bias_samples,
                  "gather directions per pixel for --bias-compensation")
      ->capture_default_str();
  cmd->add_option(
         "--traced-roughness", args->traced_roughness,
         "raster, rt-vpl: glossy surfaces rougher than this take their specular lobe from "
         "the VPLs, smoother ones from rays (walk/estimators/glossy_pass.h); 0: all from the VPLs")
      ->check(CLI::Range(0.0f, 1.0f))
      ->capture_default_str();
  cmd->add_option("--glossy-samples", args->glossy_samples,
                  "raster, rt-vpl: specular rays per pixel below --traced-roughness")
      ->check(CLI::Range(1u, 4096u))
      ->capture_default_str();
  cmd->add_option(
         "--interleave", args->interleave,
         "Raster: k > 1 splits the VPLs into k x k sets, each pixel of a k x k tile lit by "
         "one set, then a geometry-aware filter (1: every VPL shades every pixel); auto: 2 for "
         "cluster representatives in images below 512 pixels, else 4")
      ->capture_default_str();
  cmd->add_option("--interleave-edges", args->interleave_edges,
                  "Raster, interleaved: the pixels where the filter's window is cut (creases, "
                  "contacts, silhouettes): traced (rt-vpl's value over the same VPLs: exact "
                  "visibility there, and also where the shadow maps could not decide a tenth of "
                  "a pixel's light; not with --jitter), shaded (every set's light, shadow maps), "
                  "off (filled in from the window's side); auto: traced from --rounds 2 on")
      ->check(CLI::IsMember({"auto", "off", "shaded", "traced"}))
      ->capture_default_str();
  cmd->add_option("--batch", args->batch,
                  "Raster: VPLs per instanced draw of shadow maps and shading, every kind of VPL "
                  "and jitter included (1: one pass per VPL, the reference)")
      ->capture_default_str();
  cmd->add_option("--shadow-lod", args->shadow_lod,
                  "Raster, batched: the shadow faces draw only the clusters they see (cull, the "
                  "same image) and those simplified below half a texel (on); off: every triangle")
      ->check(CLI::IsMember({"on", "cull", "off"}))
      ->capture_default_str();
  cmd->add_option("--shadow-occlusion", args->shadow_occlusion,
                  "Raster, batched, shadow-lod on or cull: each face draws its nearest clusters "
                  "first and leaves out those they hide (the same image)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--shadow-helpers", args->shadow_helpers,
                  "Raster, batched: threads that draw the shadow atlases in GL contexts of their "
                  "own while the renderer's shades, once a batch draws 8000 triangles per VPL "
                  "(the same image); auto: 2 on a CPU renderer (llvmpipe) with 2 or more cores, "
                  "else 0")
      ->check(CLI::IsMember({"auto", "0", "1", "2", "3", "4", "5", "6", "7", "8"}))
      ->capture_default_str();
  cmd->add_option("--hierarchy-cache", args->hierarchy_cache,
                  "Raster: keep a scene's shadow hierarchy (batched, shadow-lod on or cull) and "
                  "its thinnest-wall scan (shadow-planes auto) between runs in "
                  "$XDG_CACHE_HOME/irad/hierarchy (else ~/.cache/irad/hierarchy); off: build and "
                  "scan every time")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--camera-lod", args->camera_lod,
                  "Raster, batched or interleaved: the G-buffer and the emitters through the "
                  "camera's cluster hierarchy (the image's frustum culled, each cluster at the "
                  "coarsest mesh whose edges and distance from the surface stay within 2 "
                  "pixels), built beside the render and kept between runs with the shadow "
                  "hierarchy (--hierarchy-cache); off: every triangle")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--visibility", args->visibility,
                  "Raster, batched: where V(y, x) comes from: maps (shadow cubes), rays (a "
                  "shadow ray per VPL and shaded pixel from the G-buffer, as rt-vpl's; no shadow "
                  "map, hierarchy or wall scan; not with --jitter, --interleave-edges shaded, "
                  "--camera-lod on or --batch 1); auto: rays on a CPU renderer (llvmpipe), where "
                  "they cost less, when the options allow, else maps")
      ->check(CLI::IsMember({"auto", "maps", "rays"}))
      ->capture_default_str();
  cmd->add_option("--shadow-planes", args->shadow_planes,
                  "Raster, batched: a gradient per shadow texel so that walls thinner than a "
                  "texel's depth range cast their shadow (off: cheaper lookups that trust the "
                  "receiver's plane, so light passes under such walls); "
                  "auto: on where the scene has such walls, looked for when shadow maps are "
                  "first drawn (never where --visibility auto traces the shadows)")
      ->check(CLI::IsMember({"auto", "on", "off"}))
      ->capture_default_str();
  cmd->add_option("--jitter", args->jitter,
                  "Raster: every VPL pass and the emitters at a sub-pixel offset from the path's "
                  "low-discrepancy point (antialiased edges without multisampling); pt: each "
                  "sample through a uniform point of its pixel (the antialiased reference)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--gl", args->gl,
                  "OpenGL for the raster: auto (a GPU through EGL if there is one, else OSMesa), "
                  "egl (a device, or Mesa's surfaceless platform), osmesa")
      ->check(CLI::IsMember({"auto", "egl", "osmesa"}))
      ->capture_default_str();
  cmd->add_option("--gl-device", args->gl_device, "EGL device index (implies EGL)");
  cmd->add_flag("--partial", args->partial,
                "On SIGINT or SIGTERM, write the image accumulated so far as OUT.partial.EXT "
                "(without it an interrupted render writes nothing)");
  cmd->add_option("--max-triangles", args->max_triangles,
                  "Refuse scenes with more triangles (all instances)")
      ->capture_default_str();
  cmd->add_option("--max-file-size", args->max_file_mib,
                  "Refuse scene files and external files larger than this many MiB")
      ->capture_default_str();
  cmd->add_option("--max-texture-size", args->max_texture_size,
                  "Refuse images with more texels per side")
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", args->quiet, "No progress, warnings or summary on stderr");
  cmd->callback([args, &commands] { commands.selected = [args] { return run_render(*args); }; });
}

} // namespace irad::apps
