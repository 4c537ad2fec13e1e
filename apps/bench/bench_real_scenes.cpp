#include "apps/bench/bench_real_scenes.h"

#include "core/gltf/loader.h"
#include "core/gltf/writer.h"
#include "core/scene/scene_builder.h"
#include "core/util/error.h"

#include <algorithm>
#include <array>

namespace irad::apps {

namespace {

// Where the bench puts the eye and the light of one file (world units of the file). The light
// is a point light of radiant intensity `intensity` (no photometric units, core/scene/scene.h).
struct RealScene {
  const char* name;
  const char* file; // under the shared folder
  glm::vec3 look_from, look_at;
  glm::vec3 light;
  float intensity;
  // Its materials as the file gives them, the spheres ("Glass") polished metal (metallic 1,
  // roughness 0.2); false: every material declared Lambertian.
  bool glossy = false;
};

// zdm2: a corridor looking through archways into the next hall, the light under the corridor's
// ceiling 6 units ahead. godot: a corner room (x, z in 1.67..5, floor y = 0.05, ceiling 4.95)
// looking along -x past a column of four glass spheres at a doorway to the dark room beyond,
// the light high in the room's far corner. godot_glossy: the same room as the file means it (its
// walls a dielectric of roughness 0.5) with metal spheres.
const std::array<RealScene, 3> kScenes{{
    {"zdm2",
     "zdm2/zdm2.glb",
     {-17.3f, 1.8f, 2.6f},
     {17.0f, 0.5f, 2.6f},
     {-11.0f, 6.5f, 2.6f},
     10.0f},
    {"godot",
     "godot_occlusion_room/room.glb",
     {4.7f, 2.5f, 2.2f},
     {-3.0f, 1.8f, 2.2f},
     {3.3f, 4.2f, 4.2f},
     15.0f},
    {"godot_glossy",
     "godot_occlusion_room/room.glb",
     {4.7f, 2.5f, 2.2f},
     {-3.0f, 1.8f, 2.2f},
     {3.3f, 4.2f, 4.2f},
     15.0f,
     true},
}};

const RealScene& find(const std::string& name) {
  for (const RealScene& s : kScenes)
    if (name == s.name) return s;
  throw Error("", "--scene", "unknown real scene '" + name + "' (zdm2, godot, godot_glossy)");
}

} // namespace

bool is_real_scene(const std::string& name) {
  return std::any_of(kScenes.begin(), kScenes.end(),
                     [&](const RealScene& s) { return name == s.name; });
}

Scene load_real_scene(const std::string& name, const std::string& shared_dir, Log& log) {
  const RealScene& r = find(name);
  Scene s = load_gltf(shared_dir + "/" + r.file, log);
  for (Material& m : s.materials) {
    if (!r.glossy) { // Lambertian by declaration (bench_real_scenes.h)
      m.metallic = 0.0f;
      m.specular_factor = 0.0f;
    } else if (m.name == "Glass") {
      m.metallic = 1.0f;
      m.roughness = 0.2f;
    }
  }
  s.cameras = {look_at(r.look_from, r.look_at, {0.0f, 1.0f, 0.0f}, glm::radians(60.0f))};
  s.cameras[0].name = "bench camera";
  PunctualLight light;
  light.name = "bench light";
  light.position = r.light;
  light.intensity = glm::vec3(r.intensity);
  s.lights = {light};
  return s;
}

std::string write_lit_copy(const Scene& scene, const std::string& name,
                           const std::string& out_dir) {
  const std::string path = out_dir + "/lit_" + name + ".gltf";
  write_gltf(scene, path);
  return path;
}

} // namespace irad::apps
