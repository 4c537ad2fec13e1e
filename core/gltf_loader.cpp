#include "core/gltf_loader.h"

#include "core/gltf_cameras_lights.h"
#include "core/gltf_context.h"
#include "core/gltf_geometry.h"
#include "core/gltf_materials.h"
#include "core/gltf_nodes.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <string_view>
#include <system_error>

namespace irad {

namespace {

using gltf::Context;

// Extensions whose meaning irad implements; any other required extension is an error.
constexpr std::array<std::string_view, 2> kSupportedExtensions{"KHR_lights_punctual",
                                                               "KHR_materials_emissive_strength"};

bool supported(const std::string& extension) {
  return std::find(kSupportedExtensions.begin(), kSupportedExtensions.end(), extension) !=
         kSupportedExtensions.end();
}

// tinygltf reports newline-separated lines; this joins the non-empty ones with "; ", each cut
// to at most kMaxLine characters (tinygltf quotes whole data URIs).
std::string one_line(const std::string& text) {
  constexpr std::size_t kMaxLine = 240;
  std::string out;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    line.erase(std::remove(line.begin(), line.end(), '\r'), line.end());
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    const auto last = line.find_last_not_of(" \t");
    line = line.substr(first, last - first + 1);
    if (line.size() > kMaxLine) line = line.substr(0, kMaxLine) + "...";
    out += (out.empty() ? "" : "; ") + line;
  }
  return out;
}

// Whether the file is binary glTF: it starts with the "glTF" magic, or its extension is .glb.
// Throws Error(file, "", "cannot open file: <reason>") when it cannot be read.
bool is_binary(const std::filesystem::path& path, const std::string& file) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw Error(file, "", "cannot open file: is a directory");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(file, "", "cannot open file: " + std::generic_category().message(errno));
  char magic[4] = {};
  in.read(magic, sizeof magic);
  if (in.gcount() == 4 && std::memcmp(magic, "glTF", 4) == 0) return true;
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return extension == ".glb";
}

// tinygltf image callback (user data: the model being loaded). tinygltf 2.7 hands an image's
// bufferView bytes to the decoder without checking that the view lies within its buffer; this
// checks it first, then delegates to tinygltf's stb_image decoder (which expands to RGBA).
bool load_image(tinygltf::Image* image, int index, std::string* err, std::string* warn, int width,
                int height, const unsigned char* bytes, int size, void* user) {
  const auto* model = static_cast<const tinygltf::Model*>(user);
  if (image->bufferView >= 0) {
    const tinygltf::BufferView& view = model->bufferViews[std::size_t(image->bufferView)];
    const std::size_t available = model->buffers[std::size_t(view.buffer)].data.size();
    if (view.byteLength > available || view.byteOffset > available - view.byteLength) {
      *err += "images[" + std::to_string(index) + "]: bufferView exceeds its buffer\n";
      return false;
    }
  }
  return tinygltf::LoadImageData(image, index, err, warn, width, height, bytes, size, nullptr);
}

tinygltf::Model parse(const std::filesystem::path& path, const std::string& file, Log& log) {
  const bool binary = is_binary(path, file);
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&load_image, &model);
  std::string err;
  std::string warn;
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, file)
                         : loader.LoadASCIIFromFile(&model, &err, &warn, file);
  if (!one_line(warn).empty()) log.warn(file + ": " + one_line(warn));
  if (!ok || !one_line(err).empty()) {
    throw Error(file, "", err.empty() ? "tinygltf could not load the file" : one_line(err));
  }
  return model;
}

void check_asset(const Context& ctx) {
  const tinygltf::Asset& asset = ctx.model.asset;
  if (asset.version.rfind("2.", 0) != 0) {
    ctx.fail("asset.version", "unsupported glTF version '" + asset.version + "'");
  }
  if (!asset.minVersion.empty() && asset.minVersion != "2.0") {
    ctx.fail("asset.minVersion", "unsupported glTF minVersion '" + asset.minVersion + "'");
  }
}

void check_extensions(const Context& ctx) {
  for (const std::string& name : ctx.model.extensionsRequired) {
    if (!supported(name)) {
      ctx.fail("extensionsRequired", "unsupported required extension '" + name + "'");
    }
  }
  for (const std::string& name : ctx.model.extensionsUsed) {
    if (!supported(name)) {
      ctx.warn("extension '" + name + "' is not supported; ignored");
    }
  }
}

// Scene-building state: the triangle soup and the lazily added default material.
class Builder {
public:
  Builder(const Context& ctx, Scene& scene) : ctx_(ctx), scene_(scene) {}

  void add(const gltf::NodeInstance& instance) {
    const tinygltf::Node& n = ctx_.model.nodes[instance.node];
    if (n.mesh >= 0) add_mesh(std::size_t(n.mesh), instance.world);
    if (n.camera >= 0) {
      auto camera = gltf::place_camera(ctx_, std::size_t(n.camera), instance.node, instance.world);
      if (camera) scene_.cameras.push_back(std::move(*camera));
    }
    if (const int l = gltf::node_light(ctx_, instance.node); l >= 0) {
      auto light = gltf::place_light(ctx_, std::size_t(l), instance.node, instance.world);
      if (light) scene_.lights.push_back(std::move(*light));
    }
  }

  void finish() { gltf::finish_geometry(ctx_, std::move(soup_), scene_); }

private:
  void add_mesh(std::size_t mesh, const glm::dmat4& world) {
    const auto& primitives = ctx_.model.meshes[mesh].primitives;
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      const std::string where = gltf::element("meshes", mesh) + gltf::element(".primitives", p);
      const std::uint32_t material = material_of(primitives[p], where);
      gltf::append_primitive(ctx_, mesh, p, world, material, soup_);
    }
  }

  // Scene material of a primitive; warns when its textures have no TEXCOORD_0 to follow.
  std::uint32_t material_of(const tinygltf::Primitive& p, const std::string& where) {
    if (p.material < 0) return default_material();
    const std::size_t m =
        gltf::checked_index(ctx_, p.material, ctx_.model.materials.size(), where, "material");
    const Material& material = scene_.materials[m];
    const bool textured = material.base_color_texture >= 0 || material.emissive_texture >= 0;
    if (textured && !p.attributes.count("TEXCOORD_0")) {
      ctx_.warn(where + ": textured material without TEXCOORD_0; (0, 0) is used");
    }
    return std::uint32_t(m);
  }

  // glTF's default material (white, not emissive), added on first use.
  std::uint32_t default_material() {
    if (!default_material_) {
      Material m;
      m.name = "default";
      scene_.materials.push_back(m);
      default_material_ = std::uint32_t(scene_.materials.size() - 1);
    }
    return *default_material_;
  }

  const Context& ctx_;
  Scene& scene_;
  gltf::Soup soup_;
  std::optional<std::uint32_t> default_material_;
};

} // namespace

Scene load_gltf(const std::filesystem::path& path, Log& log) {
  const std::string file = path.string();
  const tinygltf::Model model = parse(path, file, log);
  const Context ctx{model, file, log};
  check_asset(ctx);
  check_extensions(ctx);

  Scene scene;
  scene.source = file;
  gltf::convert_materials(ctx, scene);
  Builder builder(ctx, scene);
  for (const gltf::NodeInstance& instance : gltf::flatten_scene(ctx)) builder.add(instance);
  builder.finish();

  if (scene.triangles.empty()) throw Error(file, "", "no triangles");
  if (!scene.has_emitters() && scene.lights.empty()) {
    throw Error(file, "", "no light: no emissive material and no KHR_lights_punctual light");
  }
  if (scene.cameras.empty()) scene.cameras.push_back(gltf::default_camera(scene.bounds));
  return scene;
}

} // namespace irad
