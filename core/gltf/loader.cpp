#include "core/gltf/loader.h"

#include "core/gltf/context.h"
#include "core/gltf/file.h"
#include "core/gltf/read/accessors.h"
#include "core/gltf/read/animation.h"
#include "core/gltf/read/cameras_lights.h"
#include "core/gltf/read/geometry.h"
#include "core/gltf/read/materials.h"
#include "core/gltf/read/nodes.h"
#include "core/gltf/read/skins.h"
#include "core/gltf/validate/validate.h"

#include <algorithm>
#include <array>
#include <optional>
#include <string_view>

namespace irad {

namespace {

using gltf::Context;
using gltf::json;

// Extensions whose meaning irad implements; any other required extension is an error.
constexpr std::array<std::string_view, 9> kSupportedExtensions{
    "KHR_lights_punctual",        "KHR_materials_emissive_strength",
    "KHR_texture_transform",      "KHR_mesh_quantization",
    "KHR_draco_mesh_compression", "EXT_meshopt_compression",
    "EXT_texture_webp",           "KHR_materials_ior",
    "KHR_materials_specular"};

bool supported(const std::string& extension) {
  return std::find(kSupportedExtensions.begin(), kSupportedExtensions.end(), extension) !=
         kSupportedExtensions.end();
}

std::vector<std::string> string_list(const json& root, const char* key) {
  std::vector<std::string> out;
  const json* list = gltf::member(root, key);
  if (!list || !list->is_array()) return out;
  for (const json& v : *list)
    if (v.is_string()) out.push_back(v.get<std::string>());
  return out;
}

// A required extension irad does not implement is an error naming it; a used one a warning.
void check_extensions(const Context& ctx) {
  ctx.use("/extensionsRequired");
  for (const std::string& name : string_list(ctx.root, "extensionsRequired")) {
    if (!supported(name)) {
      ctx.fail("extensionsRequired",
               "the file requires extension '" + name + "', which irad does not support");
    }
  }
  for (const std::string& name : string_list(ctx.root, "extensionsUsed")) {
    if (!supported(name)) ctx.warn("extension '" + name + "' is not supported; ignored");
  }
}

// The validator's view of the resolved buffers.
std::vector<gltf::BufferBytes> buffer_views(const gltf::SceneFile& f,
                                            const std::vector<gltf::BufferData>& buffers) {
  std::vector<gltf::BufferBytes> out;
  for (const gltf::BufferData& b : buffers)
    out.push_back({b.bytes().data(), b.bytes().size(), b.present, false});
  if (!out.empty() && f.binary && f.bin_length == 0) out[0].glb_without_bin = true;
  return out;
}

// Materials referenced by the primitives of the meshes the reached nodes draw.
std::vector<char> referenced_materials(const Context& ctx,
                                       const std::vector<gltf::NodeInstance>& instances) {
  std::vector<char> used(ctx.count("materials"), 0);
  for (const gltf::NodeInstance& inst : instances) {
    const auto mesh = gltf::index_member(ctx.array("nodes")[inst.node], "mesh");
    if (!mesh || *mesh >= ctx.count("meshes")) continue;
    const json* prims = gltf::member(ctx.array("meshes")[std::size_t(*mesh)], "primitives");
    if (!prims || !prims->is_array()) continue;
    for (const json& p : *prims)
      if (const auto m = gltf::index_member(p, "material"); m && *m < used.size())
        used[std::size_t(*m)] = 1;
  }
  return used;
}

// Scene-building state: the triangle soup and the lazily added default material.
class Builder {
public:
  Builder(const Context& ctx, Scene& scene, std::vector<gltf::UvSets> uv, const gltf::Skins& skins)
      : ctx_(ctx), scene_(scene), uv_(std::move(uv)), skins_(skins) {
    soup_.record_deforms = track_nodes_;
  }

  // Adds what `instance` will append to the soup's size hints (gltf::add_size_hint).
  void hint(const gltf::NodeInstance& instance) {
    if (const auto mesh = gltf::index_member(ctx_.array("nodes")[instance.node], "mesh"))
      gltf::add_size_hint(ctx_, *mesh, soup_);
  }

  void add(const gltf::NodeInstance& instance) {
    const json& n = ctx_.array("nodes")[instance.node];
    if (const auto mesh = gltf::index_member(n, "mesh")) add_mesh(instance, std::size_t(*mesh));
    if (track_nodes_)
      soup_.vertex_node.resize(soup_.positions.size(), std::uint32_t(instance.node));
    if (const auto c = gltf::index_member(n, "camera")) {
      auto camera = gltf::place_camera(ctx_, std::size_t(*c), instance.node, instance.world);
      if (camera) scene_.cameras.push_back(std::move(*camera));
      if (camera) content_.camera_node.push_back(instance.node);
    }
    if (const int l = gltf::node_light(ctx_, instance.node); l >= 0) {
      auto light = gltf::place_light(ctx_, std::size_t(l), instance.node, instance.world);
      if (light) scene_.lights.push_back(std::move(*light));
      if (light) content_.light_node.push_back(instance.node);
    }
  }

  // The triangle soup into the scene; returns where each vertex, camera and light came from.
  gltf::ContentNodes finish() {
    gltf::finish_geometry(ctx_, std::move(soup_), scene_, &content_.vertex_node, &content_.deforms);
    return std::move(content_);
  }

private:
  void add_mesh(const gltf::NodeInstance& instance, std::size_t mesh) {
    ctx_.use_exact(gltf::pointer_of("meshes", mesh));
    const json& m = ctx_.array("meshes")[mesh];
    const json* primitives = gltf::member(m, "primitives");
    if (!primitives || !primitives->is_array()) return;
    gltf::PrimitivePose pose;
    pose.world = instance.world;
    pose.morph_weights = gltf::morph_weights(ctx_, instance.node, mesh);
    pose.node = instance.node;
    pose.skin = skins_.skin_of(ctx_, instance.node);
    for (std::size_t p = 0; p < primitives->size(); ++p) {
      const std::string where = gltf::element("meshes", mesh) + gltf::element(".primitives", p);
      const auto [material, uv] =
          material_of((*primitives)[p], where,
                      gltf::pointer_of("meshes", mesh) + "/primitives/" + std::to_string(p));
      gltf::append_primitive(ctx_, mesh, p, pose, material, uv, soup_);
    }
  }

  // Scene material and uv sets of a primitive, with the uv slot of its normal map (whose
  // tangents the primitive then carries).
  std::pair<std::uint32_t, gltf::UvSets> material_of(const json& p, const std::string& where,
                                                     const std::string& pointer) {
    if (!gltf::member(p, "material")) return {default_material(), {}};
    ctx_.use(pointer + "/material");
    const std::size_t m =
        *gltf::optional_index(ctx_, p, "material", ctx_.count("materials"), where);
    gltf::UvSets uv = uv_[m];
    const Material& material = scene_.materials[m];
    if (material.normal_texture >= 0) uv.tangent_slot = material.normal_map.texcoord;
    return {std::uint32_t(m), uv};
  }

  // glTF's default material (white, not emissive, metallic 1, roughness 1: the specification's
  // defaults), added on first use.
  std::uint32_t default_material() {
    if (!default_material_) {
      Material m;
      m.name = "default";
      m.metallic = 1.0f;
      m.roughness = 1.0f;
      m.specular_factor = 1.0f;
      scene_.materials.push_back(m);
      default_material_ = std::uint32_t(scene_.materials.size() - 1);
    }
    return *default_material_;
  }

  const Context& ctx_;
  Scene& scene_;
  std::vector<gltf::UvSets> uv_;
  const gltf::Skins& skins_;
  gltf::Soup soup_;
  bool track_nodes_ = !ctx_.array("animations").empty(); // vertex -> node only when it can move
  gltf::ContentNodes content_;
  std::optional<std::uint32_t> default_material_;
};

} // namespace

Scene load_gltf(const std::filesystem::path& path, Log& log, const LoadLimits& limits,
                const std::string& scene_name) {
  const std::string file = path.string();
  gltf::SceneFile f = gltf::read_scene_file(path, file, limits);
  gltf::IssueBook issues(file, {}, supported);
  const std::vector<gltf::BufferData> buffers =
      gltf::resolve_buffers(f, path.parent_path(), limits, issues);
  for (gltf::Issue& issue : gltf::validate(f.root, buffer_views(f, buffers)))
    issues.add(std::move(issue));
  gltf::DecodedViews views;
  gltf::DecodedAccessors accessors;
  const Context ctx{
      f.root, file, log, limits, issues, buffers, views, accessors, path.parent_path()};
  ctx.use("/asset");
  check_extensions(ctx);

  Scene scene;
  scene.source = file;
  const std::vector<gltf::NodeInstance> instances = gltf::flatten_scene(ctx, scene_name);
  const gltf::Skins skins(ctx, instances);
  std::vector<char> decoded_images;
  Builder builder(
      ctx, scene,
      gltf::convert_materials(ctx, referenced_materials(ctx, instances), scene, decoded_images),
      skins);
  for (const gltf::NodeInstance& instance : instances) builder.hint(instance);
  for (const gltf::NodeInstance& instance : instances) builder.add(instance);
  gltf::ContentNodes content = builder.finish();

  if (scene.triangles.empty()) throw Error(file, "", "no triangles");
  scene.animation = gltf::read_animation(ctx, instances, content, scene);
  if (scene.cameras.empty()) scene.cameras.push_back(gltf::default_camera(scene.bounds));
  gltf::check_unused_images(ctx, decoded_images);
  issues.warn_unused(log);
  return scene;
}

} // namespace irad
