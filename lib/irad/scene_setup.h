#pragma once
// A scene made ready to render: the glTF file loaded within its limits, lit (its own lights, or
// an environment), posed at a time of its animation, and the camera to render it from.
// Every function throws irad::Error("FILE", "ELEMENT", "MESSAGE") on bad input; warnings go to
// the Log (core/util/log.h: a sink of the caller's choice).
#include "core/environment/lighting.h"
#include "core/gltf/loader.h"
#include "core/scene/scene.h"
#include "core/util/log.h"

#include <optional>
#include <string>
#include <utility>

namespace irad {

struct SceneOptions {
  std::string gltf_scene;           // a glTF scene by name or index (empty: the file's default)
  LoadLimits limits;                // file size, triangles, texture size (core/gltf/loader.h)
  LightingOptions lighting;         // the environment (core/environment/lighting.h)
  std::optional<float> time;        // seconds: pose the glTF animation (else the rest pose)
  std::optional<Camera> own_camera; // replaces the file's cameras (see use_own_camera)
};

// load_gltf, light_scene, pose_at and use_own_camera in that order.
Scene load_scene(const std::string& path, const SceneOptions& options, Log& log);

// Poses the scene's animation at `time` seconds; a scene without animation is left as it is with
// one warning. Throws irad::Error naming --time unless `time` is finite.
void pose_at(Scene& scene, float time, Log& log);

// The camera selected by name or index (empty: the first); throws irad::Error listing the
// choices.
const Camera& select_camera(const Scene& scene, const std::string& which);
// Replaces the scene's cameras by `camera`, which the animation (if any) does not move.
void use_own_camera(Scene& scene, const Camera& camera);
// Image size: `size` if given, else 512 high with the camera's aspect (512x512 without one).
std::pair<int, int> image_size(const Camera& camera, std::optional<std::pair<int, int>> size);

} // namespace irad
