#include "core/gltf/writer.h"

#include "core/camera/view.h"
#include "core/util/error.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

namespace irad {

namespace {

using nlohmann::json;

constexpr int kFloat = 5126;        // GL_FLOAT
constexpr int kUnsignedInt = 5125;  // GL_UNSIGNED_INT
constexpr int kArrayBuffer = 34962; // GL_ARRAY_BUFFER
constexpr int kIndexBuffer = 34963; // GL_ELEMENT_ARRAY_BUFFER
constexpr int kTriangles = 4;

// RFC 4648 base64 with padding.
std::string base64(const std::vector<unsigned char>& bytes) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t v = std::uint32_t{bytes[i]} << 16;
    if (n > 1) v |= std::uint32_t{bytes[i + 1]} << 8;
    if (n > 2) v |= std::uint32_t{bytes[i + 2]};
    for (std::size_t k = 0; k < 4; ++k)
      out.push_back(k <= n ? kDigits[(v >> (18 - 6 * k)) & 63u] : '=');
  }
  return out;
}

json vec(const glm::vec3& v) {
  return {double(v.x), double(v.y), double(v.z)};
}

json matrix(const glm::mat4& m) {
  json out = json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out.push_back(double(m[c][r]));
  return out;
}

// The one buffer, its views (one per accessor) and the accessors.
class BufferBuilder {
public:
  // Appends `count` elements of `type` ("SCALAR", "VEC2", "VEC3") stored as 4-byte components
  // and returns the accessor's index.
  template <typename T>
  int add(const std::vector<T>& data, int component, const char* type, int target,
          json extra = json::object()) {
    const std::size_t offset = bytes_.size();
    const std::size_t length = data.size() * sizeof(T);
    bytes_.resize(offset + length);
    if (length > 0) std::memcpy(bytes_.data() + offset, data.data(), length);
    views_.push_back(
        {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}, {"target", target}});
    extra["bufferView"] = views_.size() - 1;
    extra["componentType"] = component;
    extra["count"] = data.size();
    extra["type"] = type;
    accessors_.push_back(std::move(extra));
    return static_cast<int>(accessors_.size() - 1);
  }

  void store(json& doc) const {
    if (bytes_.empty()) return;
    doc["buffers"] =
        json::array({{{"byteLength", bytes_.size()},
                      {"uri", "data:application/octet-stream;base64," + base64(bytes_)}}});
    doc["bufferViews"] = views_;
    doc["accessors"] = accessors_;
  }

private:
  std::vector<unsigned char> bytes_;
  json views_ = json::array();
  json accessors_ = json::array();
};

// Throws unless the scene is one the loader accepts back.
void validate(const Scene& scene, const std::string& file) {
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    const std::string where = fmt::format("materials[{}]", i);
    for (int c = 0; c < 3; ++c) {
      if (!(m.base_color[c] >= 0.0f && m.base_color[c] <= 1.0f))
        throw Error(file, where, fmt::format("albedo {} is outside [0, 1]", m.base_color[c]));
      if (!(m.emission[c] >= 0.0f && std::isfinite(m.emission[c])))
        throw Error(file, where, fmt::format("emission {} is not finite and >= 0", m.emission[c]));
    }
  }
  if (scene.triangle_material.size() != scene.triangles.size() ||
      scene.normals.size() != scene.positions.size() ||
      (!scene.uvs.empty() && scene.uvs.size() != scene.positions.size()))
    throw Error(file, "", "the scene's arrays have inconsistent sizes");
  for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
    const glm::uvec3& tri = scene.triangles[t];
    if (std::max({tri.x, tri.y, tri.z}) >= scene.positions.size() ||
        scene.triangle_material[t] >= scene.materials.size())
      throw Error(file, fmt::format("triangles[{}]", t), "index out of range");
  }
  for (const glm::vec3& p : scene.positions)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw Error(file, "positions", "non-finite vertex position");
  for (const Camera& c : scene.cameras)
    if (!(c.yfov > 0.0f && c.yfov < std::numbers::pi_v<float>))
      throw Error(file, "camera " + c.name, fmt::format("yfov {} is outside (0, pi)", c.yfov));
  for (const PunctualLight& l : scene.lights) {
    const std::string where = "light " + l.name;
    const glm::vec3 i = l.intensity;
    if (!(i.x >= 0.0f && i.y >= 0.0f && i.z >= 0.0f && std::isfinite(i.x + i.y + i.z)))
      throw Error(file, where, "intensity must be finite and >= 0");
    if (l.kind == PunctualLight::Kind::Point) continue;
    if (!(glm::length(l.direction) > 0.0f)) throw Error(file, where, "the light has no direction");
    if (l.kind != PunctualLight::Kind::Spot) continue;
    if (!(l.inner_cone >= 0.0f && l.inner_cone < l.outer_cone &&
          l.outer_cone <= 0.5f * std::numbers::pi_v<float>))
      throw Error(file, where, "cone angles must satisfy 0 <= inner < outer <= pi/2");
  }
}

// One primitive per material with triangles; vertices re-indexed per primitive.
json write_mesh(const Scene& scene, BufferBuilder& buffer) {
  json primitives = json::array();
  for (std::uint32_t material = 0; material < scene.materials.size(); ++material) {
    std::map<std::uint32_t, std::uint32_t> local; // scene vertex -> primitive vertex
    std::vector<std::uint32_t> indices;
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
      if (scene.triangle_material[t] != material) continue;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = scene.triangles[t][k];
        const auto [it, added] = local.emplace(v, static_cast<std::uint32_t>(positions.size()));
        if (added) {
          positions.push_back(scene.positions[v]);
          normals.push_back(scene.normals[v]);
          if (!scene.uvs.empty()) uvs.push_back(scene.uvs[v]);
        }
        indices.push_back(it->second);
      }
    }
    if (indices.empty()) continue;
    glm::vec3 lo = positions[0], hi = positions[0];
    for (const glm::vec3& p : positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    json attributes = {{"POSITION", buffer.add(positions, kFloat, "VEC3", kArrayBuffer,
                                               {{"min", vec(lo)}, {"max", vec(hi)}})},
                       {"NORMAL", buffer.add(normals, kFloat, "VEC3", kArrayBuffer)}};
    if (!uvs.empty()) attributes["TEXCOORD_0"] = buffer.add(uvs, kFloat, "VEC2", kArrayBuffer);
    primitives.push_back({{"attributes", attributes},
                          {"indices", buffer.add(indices, kUnsignedInt, "SCALAR", kIndexBuffer)},
                          {"material", material},
                          {"mode", kTriangles}});
  }
  return {{"name", "scene"}, {"primitives", primitives}};
}

// Which extensions the written materials need.
struct MaterialExtensions {
  bool strength = false; // KHR_materials_emissive_strength
  bool specular = false; // KHR_materials_specular
  bool ior = false;      // KHR_materials_ior
};

// The BRDF's factors: metallic, roughness, and KHR_materials_specular / _ior where they differ
// from glTF's defaults (a mirror: metallic 1, roughness 0).
void write_brdf(const Material& m, json& out, MaterialExtensions& used) {
  json& pbr = out["pbrMetallicRoughness"];
  pbr["metallicFactor"] = m.specular ? 1.0 : double(m.metallic);
  pbr["roughnessFactor"] = m.specular ? 0.0 : double(m.roughness);
  if (m.specular) return;
  if (m.specular_factor != 1.0f || m.specular_color != glm::vec3(1.0f)) {
    json spec = {{"specularFactor", double(m.specular_factor)}};
    if (m.specular_color != glm::vec3(1.0f)) spec["specularColorFactor"] = vec(m.specular_color);
    out["extensions"]["KHR_materials_specular"] = spec;
    used.specular = true;
  }
  if (m.ior != 1.5f) {
    out["extensions"]["KHR_materials_ior"] = {{"ior", double(m.ior)}};
    used.ior = true;
  }
}

json write_material(const Material& m, MaterialExtensions& used) {
  const glm::vec3& c = m.base_color;
  json out = {
      {"name", m.name},
      {"pbrMetallicRoughness", {{"baseColorFactor", {double(c.x), double(c.y), double(c.z), 1.0}}}},
      {"doubleSided", m.double_sided}};
  write_brdf(m, out, used);
  const double peak = std::max({m.emission.x, m.emission.y, m.emission.z});
  if (peak > 1.0) {
    const glm::dvec3 e(m.emission);
    out["emissiveFactor"] = {e.x / peak, e.y / peak, e.z / peak};
    out["extensions"]["KHR_materials_emissive_strength"] = {{"emissiveStrength", peak}};
    used.strength = true;
  } else if (peak > 0.0) {
    out["emissiveFactor"] = vec(m.emission);
  }
  return out;
}

json write_camera(const Scene& scene, const Camera& c) {
  const float znear = c.znear > 0.0f ? c.znear : make_view(c, scene.bounds, 1, 1).znear;
  json perspective = {{"yfov", double(c.yfov)}, {"znear", double(znear)}};
  if (c.aspect) perspective["aspectRatio"] = double(*c.aspect);
  if (c.zfar) perspective["zfar"] = double(*c.zfar);
  return {{"name", c.name}, {"type", "perspective"}, {"perspective", perspective}};
}

// The light's node matrix: translation to its position, -z turned to its direction (a point
// light without a direction keeps the default -z).
glm::mat4 light_frame(const PunctualLight& l) {
  const float length = glm::length(l.direction);
  if (!(length > 0.0f && std::isfinite(length))) return glm::translate(glm::mat4(1.0f), l.position);
  const glm::vec3 z = -l.direction / length;
  const glm::vec3 helper = std::abs(z.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  const glm::vec3 x = glm::normalize(glm::cross(helper, z));
  const glm::vec3 y = glm::cross(z, x);
  return {glm::vec4(x, 0), glm::vec4(y, 0), glm::vec4(z, 0), glm::vec4(l.position, 1)};
}

json write_light(const PunctualLight& l) {
  const double peak = std::max({l.intensity.x, l.intensity.y, l.intensity.z});
  const glm::dvec3 colour = peak > 0.0 ? glm::dvec3(l.intensity) / peak : glm::dvec3(1.0);
  json out = {{"name", l.name},
              {"color", {colour.x, colour.y, colour.z}},
              {"intensity", std::max(peak, 0.0)}};
  if (l.kind == PunctualLight::Kind::Spot) {
    out["type"] = "spot";
    out["spot"] = {{"innerConeAngle", double(l.inner_cone)},
                   {"outerConeAngle", double(l.outer_cone)}};
  } else {
    out["type"] = l.kind == PunctualLight::Kind::Directional ? "directional" : "point";
  }
  return out;
}

json document(const Scene& scene) {
  json doc = {{"asset", {{"version", "2.0"}, {"generator", "irad write_gltf"}}}};
  BufferBuilder buffer;
  json nodes = json::array();
  if (!scene.triangles.empty()) {
    doc["meshes"] = json::array({write_mesh(scene, buffer)});
    nodes.push_back({{"name", "scene"}, {"mesh", 0}});
  }
  MaterialExtensions material_extensions;
  json materials = json::array();
  for (const Material& m : scene.materials)
    materials.push_back(write_material(m, material_extensions));
  if (!materials.empty()) doc["materials"] = materials;
  json cameras = json::array();
  for (const Camera& c : scene.cameras) {
    nodes.push_back(
        {{"name", c.name}, {"camera", cameras.size()}, {"matrix", matrix(c.camera_to_world)}});
    cameras.push_back(write_camera(scene, c));
  }
  if (!cameras.empty()) doc["cameras"] = cameras;
  json lights = json::array();
  for (const PunctualLight& l : scene.lights) {
    nodes.push_back({{"name", l.name},
                     {"matrix", matrix(light_frame(l))},
                     {"extensions", {{"KHR_lights_punctual", {{"light", lights.size()}}}}}});
    lights.push_back(write_light(l));
  }
  json used = json::array();
  if (!lights.empty()) {
    doc["extensions"]["KHR_lights_punctual"] = {{"lights", lights}};
    used.push_back("KHR_lights_punctual");
  }
  if (material_extensions.strength) used.push_back("KHR_materials_emissive_strength");
  if (material_extensions.specular) used.push_back("KHR_materials_specular");
  if (material_extensions.ior) used.push_back("KHR_materials_ior");
  if (!used.empty()) doc["extensionsUsed"] = used;
  json roots = json::array();
  for (std::size_t i = 0; i < nodes.size(); ++i) roots.push_back(i);
  doc["nodes"] = nodes;
  doc["scenes"] = json::array({{{"nodes", roots}}});
  doc["scene"] = 0;
  buffer.store(doc);
  return doc;
}

} // namespace

void write_gltf(const Scene& scene, const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  const std::string file = path.string();
  validate(scene, file);
  const fs::path parent = path.parent_path();
  if (!parent.empty() && !fs::is_directory(parent))
    throw Error(file, "", fmt::format("output folder '{}' does not exist", parent.string()));
  const std::string text = document(scene).dump(1) + '\n';
  const fs::path tmp = file + ".tmp";
  std::error_code ec;
  {
    std::ofstream out(tmp, std::ios::binary);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) {
      fs::remove(tmp, ec);
      throw Error(file, "", "cannot write");
    }
  }
  fs::rename(tmp, path, ec);
  if (!ec) return;
  const std::string reason = ec.message();
  fs::remove(tmp, ec);
  throw Error(file, "", "cannot write: " + reason);
}

} // namespace irad
