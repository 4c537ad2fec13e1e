#include "apps/render_pipeline.h"

#include "core/animation.h"

#include "core/error.h"
#include "core/gltf/loader.h"
#include "walk/bias_compensation.h"
#include "walk/mirror_pass.h"
#include "walk/ray_scene.h"
#include "walk/vpl_tracer.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <memory>

namespace irad::apps {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

bool all_digits(const std::string& s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}

// Rewrites one stderr line at most ~10 times per second.
class ProgressLine {
public:
  explicit ProgressLine(bool enabled) : enabled_(enabled) {}
  ~ProgressLine() {
    if (enabled_ && drawn_) std::fputs("\r\033[K", stderr);
  }
  void operator()(std::size_t done, std::size_t total) {
    if (!enabled_) return;
    const auto now = Clock::now();
    if (done != total && now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    drawn_ = true;
    std::fprintf(stderr, "\rirad: rendering %zu/%zu (%.0f%%)", done, total,
                 total ? 100.0 * static_cast<double>(done) / static_cast<double>(total) : 100.0);
    std::fflush(stderr);
  }

private:
  bool enabled_;
  bool drawn_ = false;
  Clock::time_point last_{};
};

} // namespace

const Camera& select_camera(const Scene& scene, const std::string& which) {
  if (scene.cameras.empty()) throw Error(scene.source, "cameras", "no camera");
  if (which.empty()) return scene.cameras.front();
  if (all_digits(which)) {
    const unsigned long index = std::stoul(which);
    if (index < scene.cameras.size()) return scene.cameras[index];
  }
  std::string names;
  for (std::size_t i = 0; i < scene.cameras.size(); ++i) {
    if (scene.cameras[i].name == which) return scene.cameras[i];
    names += fmt::format("{}{} '{}'", i ? ", " : "", i, scene.cameras[i].name);
  }
  throw Error(scene.source, "--camera", fmt::format("no camera '{}' (have: {})", which, names));
}

void use_own_camera(Scene& scene, const Camera& camera) {
  scene.cameras = {camera};
  if (scene.animation && !scene.animation->camera_node.empty()) {
    auto animation = std::make_shared<Animation>(*scene.animation);
    animation->camera_node.clear(); // Animation::pose then leaves the camera where it is
    scene.animation = std::move(animation);
  }
}

std::pair<int, int> image_size(const Camera& camera, std::optional<std::pair<int, int>> size) {
  if (size) return *size;
  // An orthographic camera's rectangle fixes the aspect (xmag / ymag); a perspective one's is
  // the file's aspectRatio, else square.
  const float aspect = camera.orthographic && camera.ymag > 0.0f ? camera.xmag / camera.ymag
                                                                 : camera.aspect.value_or(1.0f);
  const int width = static_cast<int>(std::lround(512.0f * aspect));
  return {std::clamp(width, 1, 16384), 512};
}

namespace {

void run_raster(const RenderRequest& request, RenderResult& r, Log& log) {
  const auto t0 = Clock::now();
  RasterOptions options = request.raster;
  options.cancel = request.cancel;
  options.gl_messages = [&log](const std::string& message) { log.warn(message); };
  RasterRenderer raster(r.scene, options);
  r.gl = raster.description();
  RasterTimings timings;
  ProgressLine progress(request.progress);
  r.image = raster.render(r.view, r.vpls, &timings, std::ref(progress));
  r.seconds.raster = since(t0);
  r.seconds.readback = timings.readback;
  r.passes = timings.passes;
}

// Adds the clamp's residual R(x) to the clamped image.
void compensate(const RenderRequest& request, const RayScene& rays, RenderResult& r) {
  const auto t0 = Clock::now();
  BiasCompensationOptions options;
  options.clamp = request.raster.clamp;
  options.samples = request.bias_samples;
  options.seed = request.pt.seed;
  options.threads = request.pt.threads;
  const Image residual = clamp_residual(r.scene, rays, r.view, r.vpls, options);
  for (std::size_t i = 0; i < residual.pixels().size(); ++i)
    r.image.pixels()[i] += glm::vec4(glm::vec3(residual.pixels()[i]), 0.0f);
  r.seconds.compensation = since(t0);
}

void pose_at(Scene& scene, float time, Log& log) {
  if (!std::isfinite(time)) throw Error("", "--time", "must be a finite number of seconds");
  if (!scene.animation) {
    log.warn(scene.source + ": the scene has no animation; --time is ignored");
    return;
  }
  scene.animation->pose(time, scene);
}

} // namespace

RenderResult render_scene(const RenderRequest& request, Log& log) {
  RenderResult r;
  const auto cancelled = [&] {
    r.cancelled = r.cancelled || (request.cancel != nullptr && request.cancel->load());
    return r.cancelled;
  };
  const auto t0 = Clock::now();
  r.scene = load_gltf(request.scene_path, log, request.limits, request.gltf_scene);
  light_scene(r.scene, request.lighting, log);
  if (request.time) pose_at(r.scene, *request.time, log);
  if (request.own_camera) use_own_camera(r.scene, *request.own_camera);
  r.camera = select_camera(r.scene, request.camera);
  const auto [width, height] = image_size(r.camera, request.size);
  r.view = make_view(r.camera, r.scene.bounds, width, height);
  const RayScene rays(r.scene);
  r.seconds.load = since(t0);
  if (r.scene.has_specular() && request.bias_compensation)
    throw Error(request.scene_path, "--bias-compensation",
                "the clamp's residual does not handle mirrors (specular materials) yet");

  if (cancelled()) {
    // Interrupted while loading: nothing was rendered.
  } else if (request.estimator == Estimator::Pt) {
    const auto t1 = Clock::now();
    ProgressLine progress(request.progress);
    PathTracerOptions pt = request.pt;
    pt.cancel = request.cancel;
    r.image =
        path_trace(r.scene, rays, r.view, pt, [&](int done, int rows) { progress(done, rows); });
    r.seconds.trace = since(t1);
  } else {
    const auto t1 = Clock::now();
    r.vpls = quasi_random_walk(r.scene, rays, request.walk, log);
    r.seconds.walk = since(t1);
    if (cancelled()) {
      // Interrupted during the walk: nothing was rendered.
    } else if (request.estimator == Estimator::Raster) {
      run_raster(request, r, log);
      if (r.scene.has_specular() && !cancelled()) { // visible mirrors: walk/mirror_pass.h
        const auto t2 = Clock::now();
        add_mirror_pass(r.scene, rays, r.view, r.vpls,
                        {request.raster.clamp, request.pt.threads, request.cancel}, r.image);
        r.seconds.trace = since(t2);
      }
    } else {
      const auto t2 = Clock::now();
      r.image = trace_vpls(r.scene, rays, r.view, r.vpls,
                           {request.raster.clamp, request.pt.threads, request.cancel});
      r.seconds.trace = since(t2);
    }
    if (request.bias_compensation && !cancelled()) compensate(request, rays, r);
    // Not with mirrors (the estimate ignores mirrored VPLs): the stats show -1.
    if (request.clamped_fraction && !r.scene.has_specular() && !cancelled())
      r.clamped_fraction = clamped_fraction(r.scene, rays, r.view, r.vpls, request.raster.clamp);
  }
  r.seconds.total = since(t0);
  if (cancelled()) return r;

  if (const std::size_t bad = r.image.non_finite_count(); bad > 0)
    throw Error(request.scene_path, "image",
                fmt::format("{} pixels are NaN or Inf; nothing written", bad));
  return r;
}

} // namespace irad::apps
