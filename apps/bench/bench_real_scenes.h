#pragma once
// The bench's real scenes: third-party levels of ../shared/scenes (README.md there), which carry
// no light and no camera. The bench adds one point light and one camera inside a room of each,
// placed by hand from test renders, and writes that lit copy next to its results. zdm2's and
// godot's materials are declared Lambertian (metallic 0, specular 0: albedo = base colour), the
// model the bench's figures for them were measured on; godot_glossy is the glossy interior: the
// room's materials as the file gives them (a dielectric of roughness 0.5) and its spheres metal.
#include "core/scene/scene.h"
#include "core/util/log.h"

#include <string>

namespace irad::apps {

// Whether `name` is one: zdm2 (zdm2/zdm2.glb, 58k triangles, no materials: albedo 1 here), godot
// or godot_glossy (godot_occlusion_room/room.glb, 64k triangles, 17 meshes).
bool is_real_scene(const std::string& name);

// Loads real scene `name` from shared_dir and adds its light and camera (the scene's only ones).
// Throws irad::Error for an unknown name or a file load_gltf rejects (a missing one included).
Scene load_real_scene(const std::string& name, const std::string& shared_dir, Log& log);

// The lit copy: write_gltf (core/gltf/writer.h) of the scene to OUT_DIR/lit_NAME.gltf, which
// `irad render` reads with the same light and camera. Returns the path written.
std::string write_lit_copy(const Scene& scene, const std::string& name, const std::string& out_dir);

} // namespace irad::apps
