// irad walkthrough SCENE -o frames/%04d.png: real-time instant radiosity frame by frame (seed
// section 5.1.3), written headlessly. Modes: ring (each frame traces one new path into a ring of
// the N most recent path images; path images keep the camera they were drawn with), reshade
// (everything redrawn every frame)
// and cached (each frame replaces one path's VPLs and their shadow maps and re-shades all of
// them from the current camera), see lib/irad/walkthrough.h. glTF animations play at
// t = frame / fps; the camera can also orbit the scene (--orbit degrees per second).
#include "apps/commands.h"
#include "apps/lighting_options.h"
#include "apps/options.h"
#include "apps/window_viewer.h"
#include "core/image/image_io.h"
#include "core/util/error.h"
#include "irad/parts.h"
#include "irad/scene_setup.h"
#include "irad/walkthrough.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <optional>
#include <tuple>
#include <unistd.h>

namespace irad::apps {

namespace {

struct WalkthroughArgs {
  std::string frame_share; // --frame-share auto: this Slurm array task's share of --frames
  std::string scene, output, frames = "0:60", size = "256x256", mode = "auto", video, camera;
  std::string gltf_scene; // --scene: a glTF scene by name or index
  std::string gl = "auto";
  LookAtArgs look; // the command line's own camera (replaces the file's)
  LightingArgs lighting;
  float fps = 30.0f, orbit = 0.0f;
  std::uint32_t paths = 64;
  bool no_warmup = false, quiet = false;
  bool window = false; // interactive (apps/window_viewer.h) instead of frame files
  std::string screenshot;
  int window_frames = 0;
};

// --frames A:B, or with --frame-share auto this array task's share of it (lib/irad/parts.h).
std::pair<int, int> parse_frames(const std::string& s, const std::string& share) {
  int a = 0, b = 0;
  char colon = 0, extra = 0;
  if (std::sscanf(s.c_str(), "%d%c%d%c", &a, &colon, &b, &extra) != 3 || colon != ':' || a < 0 ||
      b <= a)
    throw Error("", "--frames", fmt::format("'{}' is not A:B with 0 <= A < B", s));
  if (share.empty()) return {a, b};
  if (share != "auto") throw Error("", "--frame-share", "'" + share + "' is not auto");
  const auto [first, end] =
      parse_part_range(share, static_cast<std::uint32_t>(b - a), "--frame-share");
  return {a + static_cast<int>(first), a + static_cast<int>(end)};
}

// The output pattern must hold exactly one integer conversion (%d, %04d, ...).
std::string frame_path(const std::string& pattern, int frame) {
  std::vector<char> buffer(pattern.size() + 32);
  std::snprintf(buffer.data(), buffer.size(), pattern.c_str(), frame);
  return buffer.data();
}

void check_pattern(const std::string& pattern) {
  const auto p = pattern.find('%');
  if (p == std::string::npos || pattern.find('%', p + 1) != std::string::npos ||
      pattern.find('d', p) == std::string::npos)
    throw Error(pattern, "-o", "needs exactly one frame number, e.g. frames/%04d.png");
  image_format_of(frame_path(pattern, 0));
  require_writable(frame_path(pattern, 0), "-o");
}

void encode_video(const WalkthroughArgs& args, int first) {
  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) {
    std::printf("walkthrough: ffmpeg is not installed: no video; the frames are written\n");
    return;
  }
  const std::string cmd = fmt::format(
      "ffmpeg -loglevel error -y -framerate {} -start_number {} -i '{}' -pix_fmt yuv420p '{}'",
      args.fps, first, args.output, args.video);
  if (std::system(cmd.c_str()) != 0) throw Error(args.video, "--video", "ffmpeg failed");
}

// Opened before any work, so that no display fails at once.
std::unique_ptr<WindowViewer> open_window(const WalkthroughArgs& args) {
  if (!args.window) return nullptr;
  WindowOptions o;
  std::tie(o.width, o.height) = parse_size_option(args.size);
  o.title = "irad " + std::filesystem::path(args.scene).filename().string();
  o.frames = args.window_frames;
  o.screenshot = args.screenshot;
  if (!o.screenshot.empty()) require_writable(o.screenshot, "--screenshot");
  return std::make_unique<WindowViewer>(o);
}

// The user flies the camera; the scene's animation plays on, one frame per displayed frame.
int run_window(WindowViewer& viewer, Walkthrough& walk, const Scene& scene, int first,
               const std::string& mode) {
  int frame = first;
  const WindowStats s = viewer.run(
      walk.camera_at(first), scene.bounds,
      [&](const Camera& c, int) { return walk.frame(frame++, c); },
      [&] { return fmt::format("{} paths, {}", walk.paths(), mode); });
  std::printf("walkthrough: window, %d frames, mode %s, N %u, l_max %d: %.1f frames/s\n", s.frames,
              mode.c_str(), walk.paths(), walk.l_max(), s.fps());
  return 0;
}

int run_walkthrough(const WalkthroughArgs& args) {
  Log log;
  log.set_quiet(args.quiet);
  const auto [first, last] = parse_frames(args.frames, args.frame_share);
  if (!args.window) check_pattern(args.output);
  const std::optional<Camera> own_camera = parse_look_at(args.look, args.camera);
  const std::unique_ptr<WindowViewer> viewer = open_window(args);
  SceneOptions scene_options;
  scene_options.gltf_scene = args.gltf_scene;
  scene_options.lighting = lighting_options(args.lighting);
  scene_options.own_camera = own_camera;
  Scene scene = load_scene(args.scene, scene_options, log);
  const Camera& chosen = select_camera(scene, args.camera);
  const std::size_t camera = static_cast<std::size_t>(&chosen - scene.cameras.data());
  WalkthroughSettings settings;
  settings.mode = args.mode == "auto" ? default_walk_mode(scene, camera, args.orbit)
                                      : parse_walk_mode(args.mode);
  settings.paths = args.paths;
  std::tie(settings.width, settings.height) = parse_size_option(args.size);
  settings.fps = args.fps;
  settings.orbit = args.orbit;
  settings.backend = parse_backend(args.gl);
  Walkthrough walk(scene, camera, settings, log);
  if (!args.no_warmup) walk.warm_up(first); // the first frame shows N paths
  const std::string mode = walk_mode_name(settings.mode);
  if (viewer) return run_window(*viewer, walk, scene, first, mode);
  using Clock = std::chrono::steady_clock;
  double render_seconds = 0.0;
  const auto t_all = Clock::now();
  const bool progress = !args.quiet && isatty(STDERR_FILENO);
  for (int f = first; f < last; ++f) {
    const auto t0 = Clock::now();
    const Image image = walk.frame(f);
    render_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
    write_image(frame_path(args.output, f), image);
    if (progress) std::fprintf(stderr, "\rirad: frame %d/%d", f - first + 1, last - first);
  }
  if (progress) std::fputs("\r\033[K", stderr);
  const int frames = last - first;
  const double total = std::chrono::duration<double>(Clock::now() - t_all).count();
  std::printf("walkthrough: %d frames %dx%d, mode %s, N %u, l_max %d%s: %.1f frames/s rendering "
              "(%.1f with image writing)\n",
              frames, settings.width, settings.height, mode.c_str(), walk.paths(), walk.l_max(),
              scene.animation ? ", animated" : "", frames / render_seconds, frames / total);
  if (!args.video.empty()) encode_video(args, first);
  return 0;
}

} // namespace

void add_walkthrough_command(CLI::App& app, Commands& commands) {
  auto args = std::make_shared<WalkthroughArgs>();
  CLI::App* cmd = app.add_subcommand("walkthrough", "Real-time frames (ring of path images)");
  cmd->add_option("scene", args->scene, "glTF 2.0 scene")->required();
  cmd->add_option("-o,--output", args->output, "Frame pattern, e.g. frames/%04d.png or .exr");
  cmd->add_option("--frames", args->frames, "Frames A:B (B exclusive)")->capture_default_str();
  cmd->add_option("--frame-share", args->frame_share,
                  "auto: render only this Slurm array task's share of --frames "
                  "(SLURM_ARRAY_TASK_ID of SLURM_ARRAY_TASK_COUNT)");
  cmd->add_option("--fps", args->fps, "Frames per second of animation time")->capture_default_str();
  cmd->add_option("--paths", args->paths, "N: the ring holds the N most recent paths")
      ->capture_default_str();
  cmd->add_option(
         "--mode", args->mode,
         "ring (seed 5.1.3: one image per path), cached (shadow maps kept, every path "
         "re-shaded from the current camera), reshade (everything redrawn), or auto: ring for a "
         "still camera, cached for a moving one")
      ->check(CLI::IsMember({"auto", "ring", "cached", "reshade"}))
      ->capture_default_str();
  cmd->add_option("--size", args->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--camera", args->camera, "Camera name or index");
  add_lighting_options(*cmd, args->lighting);
  cmd->add_option("--scene", args->gltf_scene, "glTF scene name or index (default: the file's)");
  add_look_at_options(*cmd, args->look);
  cmd->add_option("--orbit", args->orbit, "Camera orbit in degrees per second")
      ->capture_default_str();
  cmd->add_option("--gl", args->gl, "auto, egl or osmesa")
      ->check(CLI::IsMember({"auto", "egl", "osmesa"}))
      ->capture_default_str();
  cmd->add_option("--video", args->video, "Also encode OUT.mp4 with ffmpeg when it is installed");
  cmd->add_flag("--no-warmup", args->no_warmup, "Start with an empty ring");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress or warnings");
  CLI::Option* window =
      cmd->add_flag("--window", args->window,
                    "Fly through in a window (WASD/arrows, Q/E, shift, mouse drag; Esc quits); "
                    "mode cached unless --mode is given");
  cmd->add_option("--screenshot", args->screenshot, "--window: the last frame to FILE.png/.exr")
      ->needs(window);
  cmd->add_option("--window-frames", args->window_frames, "--window: stop after K frames (0: Esc)")
      ->needs(window)
      ->capture_default_str();
  cmd->callback([args, cmd, &commands] {
    if (!args->window && args->output.empty()) throw CLI::RequiredError("--output (or --window)");
    if (args->window && cmd->get_option("--mode")->count() == 0) args->mode = "cached";
    commands.selected = [args] { return run_walkthrough(*args); };
  });
}

} // namespace irad::apps
