#include "core/gltf/materials.h"

#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <tuple>
#include <utility>

namespace irad::gltf {

namespace {

Wrap wrap_mode(const Context& ctx, int mode, const std::string& where, const char* field) {
  switch (mode) {
  case TINYGLTF_TEXTURE_WRAP_REPEAT:
    return Wrap::Repeat;
  case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
    return Wrap::ClampToEdge;
  case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
    return Wrap::MirroredRepeat;
  default:
    ctx.fail(where, std::string("invalid ") + field + " " + std::to_string(mode));
  }
}

// Per-channel decoder of one image: 8- or 16-bit unsigned normalized values, optionally sRGB.
class ChannelDecoder {
public:
  ChannelDecoder(int bits, bool srgb) : bits_(bits), srgb_(srgb) {
    for (std::size_t v = 0; v < lut8_.size(); ++v) {
      lut8_[v] = srgb_to_linear(float(v) / 255.0f);
    }
  }
  // Channel k of texel t; colour channels go through the sRGB EOTF, alpha never does.
  float operator()(const unsigned char* data, std::size_t value_index, bool colour) const {
    if (bits_ == 8) {
      const unsigned char v = data[value_index];
      return colour && srgb_ ? lut8_[v] : float(v) / 255.0f;
    }
    std::uint16_t v;
    std::memcpy(&v, data + 2 * value_index, sizeof v);
    const float x = float(v) / 65535.0f;
    return colour && srgb_ ? srgb_to_linear(x) : x;
  }

private:
  int bits_;
  bool srgb_;
  std::array<float, 256> lut8_{};
};

// Texels of images[index] as linear RGBA: grey (1-2 channels) is replicated to RGB, a missing
// alpha is 1.
std::vector<glm::vec4> decode_image(const Context& ctx, std::size_t index, bool srgb) {
  const tinygltf::Image& im = ctx.model.images[index];
  const std::string name = element("images", index);
  if (im.image.empty()) {
    ctx.fail(name, "image data could not be loaded or decoded" +
                       (im.uri.empty() || im.uri.rfind("data:", 0) == 0 ? std::string()
                                                                        : " ('" + im.uri + "')"));
  }
  const int c = im.component;
  const bool layout_ok =
      im.width > 0 && im.height > 0 && c >= 1 && c <= 4 && (im.bits == 8 || im.bits == 16);
  const std::size_t texels = layout_ok ? std::size_t(im.width) * std::size_t(im.height) : 0;
  if (!layout_ok || im.image.size() != texels * std::size_t(c) * std::size_t(im.bits / 8)) {
    ctx.fail(name, "unsupported decoded image layout (" + std::to_string(c) + " channels, " +
                       std::to_string(im.bits) + " bits)");
  }
  const ChannelDecoder channel(im.bits, srgb);
  std::vector<glm::vec4> out(texels);
  const std::size_t n = std::size_t(c);
  for (std::size_t t = 0; t < texels; ++t) {
    const std::size_t k = t * n;
    const float r = channel(im.image.data(), k, true);
    const bool grey = c <= 2;
    const float g = grey ? r : channel(im.image.data(), k + 1, true);
    const float b = grey ? r : channel(im.image.data(), k + 2, true);
    const bool has_alpha = c == 2 || c == 4;
    out[t] = {r, g, b, has_alpha ? channel(im.image.data(), k + n - 1, false) : 1.0f};
  }
  return out;
}

// Converts textures on first use and hands out their index in scene.textures.
class TextureTable {
public:
  TextureTable(const Context& ctx, std::vector<Texture>& textures)
      : ctx_(ctx), textures_(textures) {}

  // Index in scene.textures of the texture referenced by `info` at element `where`.
  int get(const tinygltf::TextureInfo& info, const std::string& where, bool srgb) {
    const auto& model = ctx_.model;
    const std::size_t t = checked_index(ctx_, info.index, model.textures.size(), where, "texture");
    const tinygltf::Texture& tex = model.textures[t];
    const std::string tname = element("textures", t);
    if (tex.source < 0) ctx_.fail(tname, "has no source image (only PNG and JPEG are supported)");
    const std::size_t image = checked_index(ctx_, tex.source, model.images.size(), tname, "image");
    const int sampler =
        tex.sampler < 0
            ? -1
            : int(checked_index(ctx_, tex.sampler, model.samplers.size(), tname, "sampler"));
    if (info.texCoord != 0) {
      ctx_.warn(where + ": texCoord " + std::to_string(info.texCoord) +
                " is not supported; TEXCOORD_0 is used");
    }
    const Key key{image, sampler, srgb};
    const auto found = index_.find(key);
    if (found != index_.end()) return found->second;
    textures_.push_back(make(image, sampler, srgb));
    return index_[key] = int(textures_.size() - 1);
  }

private:
  using Key = std::tuple<std::size_t, int, bool>;

  Texture make(std::size_t image, int sampler, bool srgb) const {
    const tinygltf::Image& im = ctx_.model.images[image];
    Texture out;
    out.name = !im.name.empty() ? im.name : element("images", image);
    out.texels = decode_image(ctx_, image, srgb);
    out.width = im.width;
    out.height = im.height;
    if (sampler >= 0) {
      const tinygltf::Sampler& s = ctx_.model.samplers[std::size_t(sampler)];
      const std::string sname = element("samplers", std::size_t(sampler));
      out.wrap_s = wrap_mode(ctx_, s.wrapS, sname, "wrapS");
      out.wrap_t = wrap_mode(ctx_, s.wrapT, sname, "wrapT");
    }
    return out;
  }

  const Context& ctx_;
  std::vector<Texture>& textures_;
  std::map<Key, int> index_;
};

// Fails unless every component is finite, >= 0 and (when max_one) <= 1.
glm::vec3 colour_factor(const Context& ctx, const std::vector<double>& values, std::size_t size,
                        const std::string& where, const char* field, bool max_one) {
  if (values.size() != size) {
    ctx.fail(where, std::string(field) + " must have " + std::to_string(size) + " components");
  }
  for (double v : values) {
    if (!std::isfinite(v) || v < 0.0 || (max_one && v > 1.0)) {
      ctx.fail(where, std::string(field) + " components must be finite and " +
                          (max_one ? "in [0, 1]" : ">= 0") + ", got " + std::to_string(v));
    }
  }
  return {float(values[0]), float(values[1]), float(values[2])};
}

// KHR_materials_emissive_strength.emissiveStrength, 1 when absent.
double emissive_strength(const Context& ctx, const tinygltf::Material& m,
                         const std::string& where) {
  const auto ext = m.extensions.find("KHR_materials_emissive_strength");
  if (ext == m.extensions.end()) return 1.0;
  if (!ext->second.IsObject()) ctx.fail(where, "KHR_materials_emissive_strength must be an object");
  if (!ext->second.Has("emissiveStrength")) return 1.0;
  const tinygltf::Value& value = ext->second.Get("emissiveStrength");
  const double s = value.IsNumber() ? value.GetNumberAsDouble() : -1.0;
  if (!std::isfinite(s) || s < 0.0) {
    ctx.fail(where,
             "KHR_materials_emissive_strength.emissiveStrength must be a finite number >= 0");
  }
  return s;
}

// emissiveFactor x emissiveStrength, which must stay finite in single precision.
glm::vec3 emission(const Context& ctx, const tinygltf::Material& m, const std::string& where) {
  const std::vector<double> zero{0.0, 0.0, 0.0};
  const std::vector<double>& factor = m.emissiveFactor.empty() ? zero : m.emissiveFactor;
  const glm::dvec3 e = glm::dvec3(colour_factor(ctx, factor, 3, where, "emissiveFactor", false)) *
                       emissive_strength(ctx, m, where);
  const glm::vec3 out(e);
  if (!std::isfinite(out.x) || !std::isfinite(out.y) || !std::isfinite(out.z)) {
    ctx.fail(where, "emission (emissiveFactor x emissiveStrength) overflows");
  }
  return out;
}

Material convert(const Context& ctx, std::size_t index, TextureTable& textures) {
  const tinygltf::Material& m = ctx.model.materials[index];
  const std::string where = element("materials", index);
  Material out;
  out.name = m.name;
  const auto& pbr = m.pbrMetallicRoughness;
  out.base_color = colour_factor(ctx, pbr.baseColorFactor, 4, where + ".pbrMetallicRoughness",
                                 "baseColorFactor", true);
  if (pbr.baseColorTexture.index >= 0) {
    out.base_color_texture =
        textures.get(pbr.baseColorTexture, where + ".pbrMetallicRoughness.baseColorTexture", true);
  }
  out.emission = emission(ctx, m, where);
  if (m.emissiveTexture.index >= 0) {
    out.emissive_texture = textures.get(m.emissiveTexture, where + ".emissiveTexture", true);
  }
  out.double_sided = m.doubleSided;
  for (const auto& [value, field] : {std::pair{pbr.metallicFactor, "metallicFactor"},
                                     std::pair{pbr.roughnessFactor, "roughnessFactor"}})
    if (!std::isfinite(value) || value < 0.0 || value > 1.0)
      ctx.fail(where + ".pbrMetallicRoughness", std::string(field) + " must be in [0, 1]");
  out.specular =
      pbr.metallicFactor >= mirror_min_metallic && pbr.roughnessFactor <= mirror_max_roughness;
  return out;
}

} // namespace

void convert_materials(const Context& ctx, Scene& scene) {
  TextureTable textures(ctx, scene.textures);
  for (std::size_t i = 0; i < ctx.model.materials.size(); ++i) {
    scene.materials.push_back(convert(ctx, i, textures));
  }
}

} // namespace irad::gltf
