#include "core/gltf/loader.h"

#include "core/gltf/animation.h"
#include "core/gltf/cameras_lights.h"
#include "core/gltf/context.h"
#include "core/gltf/file.h"
#include "core/gltf/geometry.h"
#include "core/gltf/materials.h"
#include "core/gltf/nodes.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <stb_image.h>
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

// State of one tinygltf load, shared with its callbacks.
struct LoadState {
  const tinygltf::Model* model;
  const std::string* file;
  const LoadLimits* limits;
  std::uint64_t texels = 0; // decoded so far, all images
};

// tinygltf image callback. tinygltf 2.7 hands an image's bufferView bytes to the decoder without
// checking that the view lies within its buffer; this checks it, checks that the bytes are a PNG
// or JPEG within the texture limits, then delegates to tinygltf's stb_image decoder (which
// expands to RGBA).
bool load_image(tinygltf::Image* image, int index, std::string*, std::string* warn, int width,
                int height, const unsigned char* bytes, int size, void* user) {
  auto& state = *static_cast<LoadState*>(user);
  const std::string where = gltf::element("images", std::size_t(index));
  if (image->bufferView >= 0) {
    const auto& model = *state.model;
    const std::size_t v = std::size_t(image->bufferView);
    const std::size_t b = std::size_t(model.bufferViews[v].buffer);
    if (b >= model.buffers.size()) {
      throw Error(*state.file, gltf::element("bufferViews", v),
                  "buffer index " + std::to_string(b) + " out of range (" +
                      std::to_string(model.buffers.size()) + " available)");
    }
    const tinygltf::BufferView& view = model.bufferViews[v];
    const std::size_t available = model.buffers[b].data.size();
    if (view.byteLength > available || view.byteOffset > available - view.byteLength) {
      throw Error(*state.file, where, "bufferView exceeds its buffer");
    }
  }
  gltf::check_image_bytes(*state.file, where, bytes, std::size_t(size), *state.limits,
                          state.texels);
  std::string decode_error;
  if (!tinygltf::LoadImageData(image, index, &decode_error, warn, width, height, bytes, size,
                               nullptr)) {
    const char* reason = stbi_failure_reason();
    throw Error(*state.file, where,
                std::string("the image does not decode") +
                    (reason ? std::string(" (stb_image: ") + reason + ")" : ""));
  }
  return true;
}

// tinygltf's file access: only external files read_scene_file() has checked are looked up, and
// none is read beyond the size limit.
bool file_exists(const std::string& path, void*) {
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}
std::string expand_path(const std::string& path, void*) {
  return path;
}
bool read_whole_file(std::vector<unsigned char>* out, std::string*, const std::string& path,
                     void* user) {
  const auto& state = *static_cast<const LoadState*>(user);
  *out = gltf::read_file_limited(path, state.limits->max_file_bytes, *state.file, path);
  return true;
}
bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&,
                      void*) {
  *err = "irad does not write through tinygltf";
  return false;
}

tinygltf::Model parse(const std::filesystem::path& path, const std::string& file,
                      const LoadLimits& limits, Log& log) {
  const gltf::SceneFile f = gltf::read_scene_file(path, file, limits);
  tinygltf::Model model;
  LoadState state{&model, &file, &limits};
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&load_image, &state);
  loader.SetFsCallbacks({&file_exists, &expand_path, &read_whole_file, &write_whole_file, &state});
  std::string err;
  std::string warn;
  const std::string base_dir = path.parent_path().string();
  const bool ok =
      f.binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, f.bytes.data(),
                                             static_cast<unsigned int>(f.bytes.size()), base_dir)
               : loader.LoadASCIIFromString(&model, &err, &warn,
                                            reinterpret_cast<const char*>(f.bytes.data()),
                                            static_cast<unsigned int>(f.bytes.size()), base_dir);
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
    if (track_nodes_)
      soup_.vertex_node.resize(soup_.positions.size(), std::uint32_t(instance.node));
    if (n.camera >= 0) {
      auto camera = gltf::place_camera(ctx_, std::size_t(n.camera), instance.node, instance.world);
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
    gltf::finish_geometry(ctx_, std::move(soup_), scene_, &content_.vertex_node);
    return std::move(content_);
  }

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
  bool track_nodes_ = !ctx_.model.animations.empty(); // vertex -> node only when it can move
  gltf::ContentNodes content_;
  std::optional<std::uint32_t> default_material_;
};

} // namespace

Scene load_gltf(const std::filesystem::path& path, Log& log, const LoadLimits& limits) {
  const std::string file = path.string();
  const tinygltf::Model model = parse(path, file, limits, log);
  const Context ctx{model, file, log, limits};
  check_asset(ctx);
  check_extensions(ctx);

  Scene scene;
  scene.source = file;
  gltf::convert_materials(ctx, scene);
  Builder builder(ctx, scene);
  const std::vector<gltf::NodeInstance> instances = gltf::flatten_scene(ctx);
  for (const gltf::NodeInstance& instance : instances) builder.add(instance);
  const gltf::ContentNodes content = builder.finish();

  if (scene.triangles.empty()) throw Error(file, "", "no triangles");
  if (!scene.has_emitters() && scene.lights.empty()) {
    throw Error(file, "", "no light: no emissive material and no KHR_lights_punctual light");
  }
  scene.animation = gltf::read_animation(ctx, instances, content, scene);
  if (scene.cameras.empty()) scene.cameras.push_back(gltf::default_camera(scene.bounds));
  return scene;
}

} // namespace irad
