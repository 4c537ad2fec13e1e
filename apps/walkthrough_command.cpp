// irad walkthrough SCENE -o frames/%04d.png: real-time instant radiosity frame by frame (seed
// section 5.1.3), written headlessly. Modes: ring (each frame traces one new path into a ring of
// the N most recent path images; path images keep the camera they were drawn with) and reshade
// (each frame replaces one path's VPLs and re-shades all of them from the current camera).
// The camera can orbit the scene (--orbit degrees per second) to show camera motion.
#include "apps/commands.h"
#include "apps/options.h"
#include "apps/render_pipeline.h"
#include "core/error.h"
#include "core/gltf_loader.h"
#include "core/image_io.h"
#include "raster/ring_renderer.h"
#include "walk/mirror_pass.h"
#include "walk/quasi_random_walk.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <unistd.h>

namespace irad::apps {

namespace {

struct WalkthroughArgs {
  std::string scene, output, frames = "0:60", size = "256x256", mode = "ring", video, camera;
  std::string gl = "auto";
  float fps = 30.0f, orbit = 0.0f;
  std::uint32_t paths = 64;
  bool no_warmup = false, quiet = false;
};

std::pair<int, int> parse_frames(const std::string& s) {
  int a = 0, b = 0;
  char colon = 0, extra = 0;
  if (std::sscanf(s.c_str(), "%d%c%d%c", &a, &colon, &b, &extra) != 3 || colon != ':' || a < 0 ||
      b <= a)
    throw Error("", "--frames", fmt::format("'{}' is not A:B with 0 <= A < B", s));
  return {a, b};
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

// The camera turned about the vertical axis through the bounds' centre.
Camera orbit_camera(const Camera& c, const Bounds& b, float degrees) {
  Camera moved = c;
  const glm::vec3 centre = b.center();
  const glm::mat4 turn = glm::translate(glm::mat4(1.0f), centre) *
                         glm::rotate(glm::mat4(1.0f), glm::radians(degrees), {0, 1, 0}) *
                         glm::translate(glm::mat4(1.0f), -centre);
  moved.camera_to_world = turn * c.camera_to_world;
  return moved;
}

int run_walkthrough(const WalkthroughArgs& args) {
  Log log;
  log.set_quiet(args.quiet);
  const auto [first, last] = parse_frames(args.frames);
  check_pattern(args.output);
  if (!(args.fps > 0.0f)) throw Error("", "--fps", "must be positive");
  const Scene scene = load_gltf(args.scene, log);
  const Camera& camera = select_camera(scene, args.camera);
  const auto [width, height] = parse_size_option(args.size);
  const RayScene rays(scene);
  const QuasiRandomWalk walk(scene, rays, {args.paths, 64}, log);
  const std::uint32_t n = walk.header().paths;
  const auto view_at = [&](int frame) {
    const float seconds = static_cast<float>(frame) / args.fps;
    return make_view(orbit_camera(camera, scene.bounds, args.orbit * seconds), scene.bounds, width,
                     height);
  };
  RingOptions ring_options;
  ring_options.paths = n;
  ring_options.width = width;
  ring_options.height = height;
  ring_options.raster.backend = parse_backend(args.gl);
  RasterOptions raster_options = ring_options.raster;
  const bool ring_mode = args.mode == "ring";
  std::unique_ptr<RingRenderer> ring;
  std::unique_ptr<RasterRenderer> raster;
  if (ring_mode)
    ring = std::make_unique<RingRenderer>(scene, ring_options);
  else
    raster = std::make_unique<RasterRenderer>(scene, raster_options);
  std::vector<std::vector<Vpl>> paths(n);
  std::uint32_t next = 0; // the particle traced by the next frame
  if (!args.no_warmup) {  // fill the ring before the first frame
    const View v = view_at(first);
    for (; next < n; ++next) {
      walk.trace(next, paths[next]);
      if (ring) ring->replace(next, paths[next], v);
    }
  }
  using Clock = std::chrono::steady_clock;
  double render_seconds = 0.0;
  const auto t_all = Clock::now();
  const bool progress = !args.quiet && isatty(STDERR_FILENO);
  for (int f = first; f < last; ++f, ++next) {
    const auto t0 = Clock::now();
    const View v = view_at(f);
    const std::uint32_t i = next % n;
    paths[i].clear();
    walk.trace(i, paths[i]); // one new path per frame, with the current scene
    Image image;
    if (ring) {
      ring->replace(i, paths[i], v);
      image = ring->frame(v);
    } else {
      VplSet all = walk.header();
      for (const auto& p : paths) all.vpls.insert(all.vpls.end(), p.begin(), p.end());
      image = raster->render(v, all);
    }
    if (scene.has_specular()) { // visible mirrors: the ray-traced pass (walk/mirror_pass.h)
      VplSet all = walk.header();
      for (const auto& p : paths) all.vpls.insert(all.vpls.end(), p.begin(), p.end());
      add_mirror_pass(scene, rays, v, all, {raster_options.clamp, 0}, image);
    }
    render_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
    write_image(frame_path(args.output, f), image);
    if (progress) std::fprintf(stderr, "\rirad: frame %d/%d", f - first + 1, last - first);
  }
  if (progress) std::fputs("\r\033[K", stderr);
  const int frames = last - first;
  const double total = std::chrono::duration<double>(Clock::now() - t_all).count();
  std::printf("walkthrough: %d frames %dx%d, mode %s, N %u, l_max %d: %.1f frames/s rendering "
              "(%.1f with image writing)\n",
              frames, width, height, args.mode.c_str(), n, walk.header().l_max,
              frames / render_seconds, frames / total);
  if (!args.video.empty()) {
    if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) {
      std::printf("walkthrough: ffmpeg is not installed: no video; the frames are written\n");
    } else {
      const std::string cmd = fmt::format(
          "ffmpeg -loglevel error -y -framerate {} -start_number {} -i '{}' -pix_fmt yuv420p '{}'",
          args.fps, first, args.output, args.video);
      if (std::system(cmd.c_str()) != 0) throw Error(args.video, "--video", "ffmpeg failed");
    }
  }
  return 0;
}

} // namespace

void add_walkthrough_command(CLI::App& app, Commands& commands) {
  auto args = std::make_shared<WalkthroughArgs>();
  CLI::App* cmd = app.add_subcommand("walkthrough", "Real-time frames (ring of path images)");
  cmd->add_option("scene", args->scene, "glTF 2.0 scene")->required();
  cmd->add_option("-o,--output", args->output, "Frame pattern, e.g. frames/%04d.png or .exr")
      ->required();
  cmd->add_option("--frames", args->frames, "Frames A:B (B exclusive)")->capture_default_str();
  cmd->add_option("--fps", args->fps, "Frames per second of animation time")->capture_default_str();
  cmd->add_option("--paths", args->paths, "N: the ring holds the N most recent paths")
      ->capture_default_str();
  cmd->add_option("--mode", args->mode, "ring (seed 5.1.3) or reshade (re-shade every VPL)")
      ->check(CLI::IsMember({"ring", "reshade"}))
      ->capture_default_str();
  cmd->add_option("--size", args->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  cmd->add_option("--camera", args->camera, "Camera name or index");
  cmd->add_option("--orbit", args->orbit, "Camera orbit in degrees per second")
      ->capture_default_str();
  cmd->add_option("--gl", args->gl, "auto, egl or osmesa")
      ->check(CLI::IsMember({"auto", "egl", "osmesa"}))
      ->capture_default_str();
  cmd->add_option("--video", args->video, "Also encode OUT.mp4 with ffmpeg when it is installed");
  cmd->add_flag("--no-warmup", args->no_warmup, "Start with an empty ring");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress or warnings");
  cmd->callback(
      [args, &commands] { commands.selected = [args] { return run_walkthrough(*args); }; });
}

} // namespace irad::apps
