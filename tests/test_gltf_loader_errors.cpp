// The glTF loader on broken files: each malformed variant of the emissive quad is one line of
// error naming the file and the element (docs/errors.md lists the messages).
#include "tests/gltf_loader_fixture.h"
#include "tests/gltf_test_scene.h"

#include <functional>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace IRAD_UNITY_ID {

using namespace gltf_test;

// One malformed variant of the emissive quad scene.
struct BadCase {
  const char* name;
  std::function<void(Gltf&)> spoil;
  const char* element;
  const char* message;
};

// Animates node 0's `path` with one sampler (times, values of `type`) and one channel.
void animate(Gltf& g, const std::vector<float>& times, const std::vector<float>& values,
             const char* type, const char* path, const char* interpolation = "LINEAR") {
  const int t = g.accessor(g.view(times.data(), times.size() * 4), kFloat, times.size(), "SCALAR");
  const std::size_t n = values.size() / (std::string(type) == "VEC4" ? 4 : 3);
  const int v = g.accessor(g.view(values.data(), values.size() * 4), kFloat, n, type);
  json sampler = {{"input", t}, {"output", v}, {"interpolation", interpolation}};
  json channel = {{"sampler", 0}, {"target", {{"node", 0}, {"path", path}}}};
  json animation = {{"samplers", json::array({sampler})}, {"channels", json::array({channel})}};
  g.doc["animations"] = json::array({animation});
}

const BadCase kBadCases[] = {
    {"animation_times_decrease",
     [](Gltf& g) {
       animate(g, {0, 2, 1}, {0, 0, 0, 1, 0, 0, 2, 0, 0}, "VEC3", "translation");
     },
     "animations[0].samplers[0].input", "input times are not increasing"},
    {"animation_output_count",
     [](Gltf& g) {
       animate(g, {0, 1}, {0, 0, 0, 1, 0, 0}, "VEC3", "scale", "CUBICSPLINE");
     },
     "animations[0].channels[0].sampler", "output accessor's count does not match"},
    {"animation_interpolation",
     [](Gltf& g) {
       animate(g, {0, 1}, {0, 0, 0, 1, 0, 0}, "VEC3", "translation", "SMOOTH");
     },
     "animations[0].samplers[0]", "interpolation 'SMOOTH'"},
    {"animation_rotation_type",
     [](Gltf& g) {
       animate(g, {0, 1}, {0, 0, 0, 1, 0, 0}, "VEC3", "rotation");
     },
     "animations[0].channels[0].sampler", "format does not suit path 'rotation'"},
    {"animation_zero_quaternion",
     [](Gltf& g) {
       animate(g, {0, 1}, {0, 0, 0, 1, 0, 0, 0, 0}, "VEC4", "rotation");
     },
     "animations[0].samplers[0]", "zero quaternion"},
    {"animation_of_matrix_node",
     [](Gltf& g) {
       animate(g, {0, 1}, {0, 0, 0, 1, 0, 0}, "VEC3", "translation");
       g.doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
     },
     "animations[0].channels[0].target", "node that has a matrix"},
    {"animation_mirrors_mesh",
     [](Gltf& g) {
       animate(g, {0, 1}, {1, 1, 1, -1, 1, 1}, "VEC3", "scale");
     },
     "nodes[0]", "mirrors"},
    {"animation_target_node",
     [](Gltf& g) {
       animate(g, {0, 1}, {0, 0, 0, 1, 0, 0}, "VEC3", "translation");
       g.doc["animations"][0]["channels"][0]["target"]["node"] = 7;
     },
     "animations[0].channels[0]", "target node index 7"},
    {"accessor_beyond_view", [](Gltf& g) { g.doc["accessors"][0]["byteOffset"] = 8; },
     "accessors[0]", "data does not fit its buffer view"},
    {"view_beyond_buffer", [](Gltf& g) { g.doc["bufferViews"][0]["byteLength"] = 4096; },
     "bufferViews[0].byteLength", "ends past the end of its buffer"},
    {"index_out_of_range",
     [](Gltf& g) {
       g.doc["meshes"][0]["primitives"][0]["indices"] =
           g.indices(std::vector<std::uint16_t>{0, 1, 7});
     },
     "meshes[0].primitives[0].indices", "not less than the number of vertices"},
    {"position_not_vec3", [](Gltf& g) { g.doc["accessors"][0]["type"] = "VEC2"; },
     "meshes[0].primitives[0].attributes.POSITION", "format VEC2/5126 is not allowed"},
    {"no_triangles", [](Gltf& g) { g.doc["meshes"][0]["primitives"][0]["mode"] = 0; }, "",
     "no triangles"},
    {"node_cycle",
     [](Gltf& g) {
       // Below the scene's root (a cycle through a root also makes it a child: another error).
       g.doc["nodes"][0]["children"] = {1};
       g.push("nodes", {{"children", {1}}});
     },
     "nodes[1]", "the node is in a loop"},
    {"mesh_out_of_range", [](Gltf& g) { g.doc["nodes"][0]["mesh"] = 5; }, "nodes[0].mesh",
     "index 5 refers to nothing"},
    {"child_out_of_range", [](Gltf& g) { g.doc["nodes"][0]["children"] = {9}; },
     "nodes[0].children[0]", "index 9 refers to nothing"},
    {"yfov_zero",
     [](Gltf& g) {
       g.push("cameras",
              {{"type", "perspective"}, {"perspective", {{"yfov", 0.0}, {"znear", 0.1}}}});
       g.doc["nodes"][0]["camera"] = 0;
     },
     "cameras[0].perspective.yfov", "value 0.0 is out of range"},
    {"negative_emission",
     [](Gltf& g) {
       g.doc["materials"][0]["emissiveFactor"] = {-1.0, 0.0, 0.0};
     },
     "materials[0]", "emissiveFactor"},
    {"negative_emissive_strength",
     [](Gltf& g) {
       g.doc["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] =
           -2.0;
       g.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
     },
     "materials[0]", "emissiveStrength"},
    {"base_colour_above_one",
     [](Gltf& g) {
       g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {2.0, 0.0, 0.0, 1.0};
     },
     "materials[0]", "baseColorFactor"},
    {"texture_out_of_range",
     [](Gltf& g) {
       g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 3;
     },
     "materials[0].pbrMetallicRoughness.baseColorTexture.index", "index 3 refers to nothing"},
    {"light_out_of_range",
     [](Gltf& g) {
       g.doc["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}}};
       g.doc["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 2;
       g.doc["extensionsUsed"] = {"KHR_lights_punctual"};
     },
     "nodes[0].extensions.KHR_lights_punctual.light", "index 2 refers to nothing"},
    {"bad_spot_cone",
     [](Gltf& g) {
       g.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
           {{"type", "spot"}, {"spot", {{"innerConeAngle", 0.6}, {"outerConeAngle", 0.5}}}}};
       g.doc["nodes"][0]["extensions"]["KHR_lights_punctual"]["light"] = 0;
       g.doc["extensionsUsed"] = {"KHR_lights_punctual"};
     },
     "KHR_lights_punctual.lights[0]", "cone"},
    {"required_extension",
     [](Gltf& g) {
       // An extension irad does not support (it does support KHR_draco_mesh_compression).
       g.doc["extensionsUsed"] = {"EXT_lights_image_based"};
       g.doc["extensionsRequired"] = {"EXT_lights_image_based"};
     },
     "extensionsRequired", "EXT_lights_image_based"},
    {"count_mismatch",
     [](Gltf& g) {
       g.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] =
           g.vec3s({{0, 0, 1}, {0, 0, 1}});
     },
     "meshes[0].primitives[0]", "NORMAL"},
    {"scene_out_of_range", [](Gltf& g) { g.doc["scene"] = 3; }, "scene", "scene index 3"},
    {"cycle_through_root",
     [](Gltf& g) {
       g.doc["nodes"][0]["children"] = {1};
       g.push("nodes", {{"children", {0}}});
     },
     "scenes[0].nodes[0]", "a scene's node must not have a parent"},
    {"emissive_above_one",
     [](Gltf& g) {
       g.doc["materials"][0]["emissiveFactor"] = {2.0, 1.0, 1.0};
     },
     "materials[0].emissiveFactor[0]", "value 2.0 is out of range"},
    {"undeclared_extension",
     [](Gltf& g) {
       g.doc["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] =
           2.0;
     },
     "materials[0].extensions.KHR_materials_emissive_strength",
     "extension 'KHR_materials_emissive_strength' is not in extensionsUsed"},
};

TEST_F(GltfLoader, EveryBadInputIsOneLineErrorNamingFileAndElement) {
  for (const BadCase& c : kBadCases) {
    SCOPED_TRACE(c.name);
    Gltf g = emissive_quad();
    c.spoil(g);
    expect_error(g.write_gltf(dir / (std::string(c.name) + ".gltf")), c.element, c.message);
  }
}

// A target path glTF does not define (the schema allows any string, for extensions) is not an
// error: the channel is ignored with a warning.
TEST_F(GltfLoader, AnimationOfAnUnknownPathIsIgnoredWithAWarning) {
  Gltf g = emissive_quad();
  animate(g, {0, 1}, {0, 0, 0, 1, 0, 0}, "VEC3", "shear");
  const Scene s = load(g.write_gltf(dir / "shear.gltf"));
  EXPECT_EQ(s.triangle_count(), 2u);
  EXPECT_EQ(warnings_containing("animations[0].channels[0]: unknown target path 'shear'"), 1)
      << ::testing::PrintToString(warnings);
}

} // namespace
