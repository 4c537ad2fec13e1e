#include "irad/scene_setup.h"

#include "core/animation/animation.h"
#include "core/util/error.h"
#include "core/util/freed_memory.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <memory>

namespace irad {

namespace {

bool all_digits(const std::string& s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}

} // namespace

Scene load_scene(const std::string& path, const SceneOptions& options, Log& log) {
  Scene scene = load_gltf(path, log, options.limits, options.gltf_scene);
  light_scene(scene, options.lighting, log);
  if (options.time) pose_at(scene, *options.time, log);
  if (options.own_camera) use_own_camera(scene, *options.own_camera);
  release_freed_memory(); // the loader's file, decoded accessors and triangle soup
  return scene;
}

void pose_at(Scene& scene, float time, Log& log) {
  if (!std::isfinite(time)) throw Error("", "--time", "must be a finite number of seconds");
  if (!scene.animation) {
    log.warn(scene.source + ": the scene has no animation; --time is ignored");
    return;
  }
  scene.animation->pose(time, scene);
}

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

} // namespace irad
