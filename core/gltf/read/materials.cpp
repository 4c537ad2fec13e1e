#include "core/gltf/read/materials.h"

#include "core/gltf/decode/image_decode.h"
#include "core/gltf/file.h"
#include "core/gltf/read/accessors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <map>
#include <optional>
#include <tuple>
#include <utility>

namespace irad::gltf {

namespace {

Wrap wrap_mode(const Context& ctx, int mode, const std::string& where, const char* field) {
  switch (mode) {
  case 10497:
    return Wrap::Repeat;
  case 33071:
    return Wrap::ClampToEdge;
  case 33648:
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

// The encoded bytes of images[index]: its uri's data or its bufferView's bytes.
std::vector<unsigned char> image_bytes(const Context& ctx, std::size_t index) {
  const json& im = ctx.array("images")[index];
  const std::string name = element("images", index);
  if (const json* uri = member(im, "uri"); uri && uri->is_string()) {
    return uri_bytes(uri->get<std::string>(), {"image/png", "image/jpeg", "image/webp"}, ctx.folder,
                     ctx.limits, ctx.file, name);
  }
  const auto view = index_member(im, "bufferView");
  if (!view) ctx.fail(name, "has neither uri nor bufferView");
  const ViewBytes v = view_bytes(ctx, *view, name);
  return {v.data, v.data + v.length};
}

// Texels of images[index] as linear RGBA: grey (1-2 channels) is replicated to RGB, a missing
// alpha is 1. `texels` counts the decoded texels of all images against the limit.
Texture decode(const Context& ctx, std::size_t index, bool srgb, std::uint64_t& texels) {
  const std::string name = element("images", index);
  const std::vector<unsigned char> bytes = image_bytes(ctx, index);
  DecodedImage im;
  try {
    im = decode_image(bytes.data(), bytes.size(),
                      {ctx.limits.max_texture_size, ctx.limits.max_texture_texels});
  } catch (const ImageError& e) {
    ctx.fail(name, e.what());
  }
  texels += std::uint64_t(im.width) * std::uint64_t(im.height);
  if (texels > ctx.limits.max_texture_texels) {
    ctx.fail(name, fmt::format("the images hold {} texels, over the limit of {} for all images "
                               "together",
                               texels, ctx.limits.max_texture_texels));
  }
  const int c = im.channels;
  const std::size_t count = std::size_t(im.width) * std::size_t(im.height);
  if (c < 1 || c > 4 || im.pixels.size() != count * std::size_t(c) * std::size_t(im.bits / 8))
    ctx.fail(name, "unsupported decoded image layout");
  const ChannelDecoder channel(im.bits, srgb);
  Texture out;
  out.width = im.width;
  out.height = im.height;
  out.texels.resize(count);
  const std::size_t n = std::size_t(c);
  for (std::size_t t = 0; t < count; ++t) {
    const std::size_t k = t * n;
    const float r = channel(im.pixels.data(), k, true);
    const bool grey = c <= 2;
    const float g = grey ? r : channel(im.pixels.data(), k + 1, true);
    const float b = grey ? r : channel(im.pixels.data(), k + 2, true);
    const bool has_alpha = c == 2 || c == 4;
    out.texels[t] = {r, g, b, has_alpha ? channel(im.pixels.data(), k + n - 1, false) : 1.0f};
  }
  return out;
}

// The image a texture shows: EXT_texture_webp's source (irad decodes WebP), else `source`.
std::optional<std::size_t> texture_source(const Context& ctx, const json& tex,
                                          const std::string& tname) {
  const json* webp = extension(tex, "EXT_texture_webp");
  const json& holder = webp ? *webp : tex;
  const auto source = index_member(holder, "source");
  if (!source) return std::nullopt;
  const std::string where = webp ? tname + ".extensions.EXT_texture_webp" : tname;
  ctx.at("images", *source, where, "image");
  return std::size_t(*source);
}

// KHR_texture_transform as uv' = T R S uv (the extension's matrices; rotation counter-clockwise
// by `rotation` radians: R = [cos sin; -sin cos] in rows).
glm::mat3 texture_transform(const json& t) {
  const std::vector<double> offset = numbers_member(t, "offset");
  const std::vector<double> scale = numbers_member(t, "scale");
  const double rotation = number_member(t, "rotation", 0.0);
  glm::mat3 translation(1.0f), rot(1.0f), sc(1.0f);
  if (offset.size() == 2) translation[2] = glm::vec3(float(offset[0]), float(offset[1]), 1.0f);
  const float c = float(std::cos(rotation)), s = float(std::sin(rotation));
  rot[0][0] = c; // column 0: (cos, -sin)
  rot[0][1] = -s;
  rot[1][0] = s; // column 1: (sin, cos)
  rot[1][1] = c;
  if (scale.size() == 2) {
    sc[0][0] = float(scale[0]);
    sc[1][1] = float(scale[1]);
  }
  return translation * rot * sc;
}

// Converts textures on first use and hands out their index in scene.textures.
class TextureTable {
public:
  TextureTable(const Context& ctx, std::vector<Texture>& textures, std::vector<char>& decoded)
      : ctx_(ctx), textures_(textures), decoded_(decoded) {}

  // Index in scene.textures of the texture referenced by textureInfo `info` at element `where`
  // (and how it is looked up, into `map`), or -1 when the texture has no image irad can use.
  int get(const json& info, const std::string& where, bool srgb, TexCoordMap& map, int& texcoord) {
    const std::string pointer = "/" + where;
    const auto index = index_member(info, "index");
    const json& tex = ctx_.at("textures", index.value_or(~0ull >> 1), where, "texture");
    const std::size_t t = std::size_t(*index);
    const std::string tname = element("textures", t);
    texcoord = int(index_member(info, "texCoord").value_or(0));
    if (const json* tt = extension(info, "KHR_texture_transform")) {
      map.matrix = texture_transform(*tt);
      if (const auto set = index_member(*tt, "texCoord")) texcoord = int(*set);
    }
    const std::optional<std::size_t> image = texture_source(ctx_, tex, tname);
    if (!image) {
      ctx_.warn(tname + ": no image source irad can read; the texture is ignored");
      return -1;
    }
    const auto sampler_index = index_member(tex, "sampler");
    const int sampler = sampler_index
                            ? int(checked_index(ctx_, static_cast<long long>(*sampler_index),
                                                ctx_.count("samplers"), tname, "sampler"))
                            : -1;
    if (sampler >= 0) ctx_.use("samplers", std::size_t(sampler));
    const Key key{*image, sampler, srgb};
    const auto found = index_.find(key);
    if (found != index_.end()) return found->second;
    textures_.push_back(make(*image, sampler, srgb));
    return index_[key] = int(textures_.size() - 1);
  }

private:
  using Key = std::tuple<std::size_t, int, bool>;

  Texture make(std::size_t image, int sampler, bool srgb) {
    const json& im = ctx_.array("images")[image];
    Texture out = decode(ctx_, image, srgb, texels_);
    if (image < decoded_.size()) decoded_[image] = 1;
    const std::string name = string_member(im, "name");
    out.name = !name.empty() ? name : element("images", image);
    if (sampler >= 0) {
      const json& s = ctx_.array("samplers")[std::size_t(sampler)];
      const std::string sname = element("samplers", std::size_t(sampler));
      out.wrap_s = wrap_mode(ctx_, int(number_member(s, "wrapS", 10497)), sname, "wrapS");
      out.wrap_t = wrap_mode(ctx_, int(number_member(s, "wrapT", 10497)), sname, "wrapT");
    }
    return out;
  }

  const Context& ctx_;
  std::vector<Texture>& textures_;
  std::map<Key, int> index_;
  std::uint64_t texels_ = 0;
  std::vector<char>& decoded_;
};

// Fails unless every component is finite, >= 0 and (when max_one) <= 1.
glm::vec4 colour_factor(const Context& ctx, const std::vector<double>& values, std::size_t size,
                        const std::string& where, const char* field, bool max_one) {
  if (values.empty()) return size == 4 ? glm::vec4(1.0f) : glm::vec4(0.0f);
  if (values.size() != size) {
    ctx.fail(where, std::string(field) + " must have " + std::to_string(size) + " components");
  }
  for (double v : values) {
    if (!std::isfinite(v) || v < 0.0 || (max_one && v > 1.0)) {
      ctx.fail(where, std::string(field) + " components must be finite and " +
                          (max_one ? "in [0, 1]" : ">= 0") + ", got " + std::to_string(v));
    }
  }
  return {float(values[0]), float(values[1]), float(values[2]),
          size == 4 ? float(values[3]) : 0.0f};
}

// KHR_materials_emissive_strength.emissiveStrength, 1 when absent.
double emissive_strength(const Context& ctx, const json& m, const std::string& where) {
  const json* ext = extension(m, "KHR_materials_emissive_strength");
  if (!ext) return 1.0;
  const double s = number_member(*ext, "emissiveStrength", 1.0);
  if (!std::isfinite(s) || s < 0.0) {
    ctx.fail(where,
             "KHR_materials_emissive_strength.emissiveStrength must be a finite number >= 0");
  }
  return s;
}

// emissiveFactor x emissiveStrength, which must stay finite in single precision.
glm::vec3 emission(const Context& ctx, const json& m, const std::string& where) {
  const std::vector<double> factor = numbers_member(m, "emissiveFactor");
  const glm::dvec3 e =
      glm::dvec3(glm::vec3(colour_factor(ctx, factor, 3, where, "emissiveFactor", false))) *
      emissive_strength(ctx, m, where);
  const glm::vec3 out(e);
  if (!std::isfinite(out.x) || !std::isfinite(out.y) || !std::isfinite(out.z)) {
    ctx.fail(where, "emission (emissiveFactor x emissiveStrength) overflows");
  }
  return out;
}

AlphaMode alpha_mode(const Context& ctx, const json& m, const std::string& where) {
  const std::string mode = string_member(m, "alphaMode", "OPAQUE");
  if (mode == "OPAQUE") return AlphaMode::Opaque;
  if (mode == "MASK") return AlphaMode::Mask;
  if (mode == "BLEND") return AlphaMode::Blend;
  ctx.fail(where, "unknown alphaMode '" + mode + "'");
}

// The glTF TEXCOORD sets of a material's textures, in the order they were read, and the two uv
// slots they fill: the first set read takes slot 0, the next other set slot 1. A texture whose
// set finds no slot is dropped with a warning.
class SlotAssigner {
public:
  explicit SlotAssigner(const Context& ctx) : ctx_(ctx) {}

  // Puts the texture's set into map.texcoord (the slot), or returns -1 for the texture (the
  // textureInfo at element `where`).
  int assign(int texture, int set, TexCoordMap& map, const std::string& where) {
    if (texture < 0) return -1;
    if (uv_.slot0 < 0 || uv_.slot0 == set) {
      uv_.slot0 = set;
      map.texcoord = 0;
    } else if (uv_.slot1 < 0 || uv_.slot1 == set) {
      uv_.slot1 = set;
      map.texcoord = 1;
    } else {
      ctx_.warn(where + ": a third TEXCOORD set in one material; ignored");
      return -1;
    }
    return texture;
  }
  UvSets sets() const { return uv_; }

private:
  const Context& ctx_;
  UvSets uv_;
};

// A factor in [0, 1] (metallicFactor, roughnessFactor, specularFactor).
float unit_factor(const Context& ctx, const json& holder, const char* field, double fallback,
                  const std::string& where) {
  const double value = number_member(holder, field, fallback);
  if (!std::isfinite(value) || value < 0.0 || value > 1.0)
    ctx.fail(where, std::string(field) + " must be in [0, 1]");
  return float(value);
}

// KHR_materials_ior and KHR_materials_specular into `out`; the glTF defaults (ior 1.5,
// specular 1, colour 1) without them.
void read_specular(const Context& ctx, const json& m, const std::string& where,
                   TextureTable& textures, SlotAssigner& slots, Material& out) {
  out.ior = 1.5f;
  out.specular_factor = 1.0f;
  out.specular_color = glm::vec3(1.0f);
  if (const json* ior = extension(m, "KHR_materials_ior")) {
    const double v = number_member(*ior, "ior", 1.5);
    if (!std::isfinite(v) || (v < 1.0 && v != 0.0))
      ctx.fail(where + ".extensions.KHR_materials_ior", "ior must be 0 or at least 1");
    out.ior = float(v);
  }
  const json* spec = extension(m, "KHR_materials_specular");
  if (spec == nullptr) return;
  const std::string sw = where + ".extensions.KHR_materials_specular";
  out.specular_factor = unit_factor(ctx, *spec, "specularFactor", 1.0, sw);
  const std::vector<double> colour = numbers_member(*spec, "specularColorFactor");
  if (!colour.empty())
    out.specular_color = glm::vec3(colour_factor(ctx, colour, 3, sw, "specularColorFactor", false));
  int set = 0;
  if (const json* t = member(*spec, "specularTexture")) {
    const std::string at = sw + ".specularTexture";
    const int tex = textures.get(*t, at, false, out.specular_map, set);
    out.specular_texture = slots.assign(tex, set, out.specular_map, at);
  }
  if (const json* t = member(*spec, "specularColorTexture")) {
    const std::string at = sw + ".specularColorTexture";
    const int tex = textures.get(*t, at, true, out.specular_color_map, set);
    out.specular_color_texture = slots.assign(tex, set, out.specular_color_map, at);
  }
}

// metallicFactor, roughnessFactor and metallicRoughnessTexture (linear; B metallic, G roughness).
void read_metallic_roughness(const Context& ctx, const json& pbr, const std::string& pw,
                             TextureTable& textures, SlotAssigner& slots, Material& out) {
  out.metallic = unit_factor(ctx, pbr, "metallicFactor", 1.0, pw);
  out.roughness = unit_factor(ctx, pbr, "roughnessFactor", 1.0, pw);
  out.specular = out.metallic >= mirror_min_metallic && out.roughness <= mirror_max_roughness;
  if (const json* t = member(pbr, "metallicRoughnessTexture")) {
    int set = 0;
    const std::string at = pw + ".metallicRoughnessTexture";
    const int tex = textures.get(*t, at, false, out.metallic_roughness_map, set);
    out.metallic_roughness_texture = slots.assign(tex, set, out.metallic_roughness_map, at);
  }
}

// normalTexture (linear) and its scale.
void read_normal_map(const Context& ctx, const json& m, const std::string& where,
                     TextureTable& textures, SlotAssigner& slots, Material& out) {
  const json* t = member(m, "normalTexture");
  if (t == nullptr) return;
  const double scale = number_member(*t, "scale", 1.0);
  if (!std::isfinite(scale)) ctx.fail(where + ".normalTexture", "scale must be finite");
  out.normal_scale = float(scale);
  int set = 0;
  const std::string at = where + ".normalTexture";
  const int tex = textures.get(*t, at, false, out.normal_map, set);
  out.normal_texture = slots.assign(tex, set, out.normal_map, at);
}

Material convert(const Context& ctx, std::size_t index, TextureTable& textures, UvSets& uv) {
  const json& m = ctx.array("materials")[index];
  const std::string where = element("materials", index);
  ctx.use("materials", index);
  Material out;
  out.name = string_member(m, "name");
  const json* pbr_ptr = member(m, "pbrMetallicRoughness");
  const json& pbr = pbr_ptr ? *pbr_ptr : json::object();
  const std::string pw = where + ".pbrMetallicRoughness";
  const glm::vec4 base =
      colour_factor(ctx, numbers_member(pbr, "baseColorFactor"), 4, pw, "baseColorFactor", true);
  out.base_color = glm::vec3(base);
  out.base_alpha = base.a;
  SlotAssigner slots(ctx);
  int set = 0;
  if (const json* t = member(pbr, "baseColorTexture")) {
    const std::string at = pw + ".baseColorTexture";
    const int tex = textures.get(*t, at, true, out.base_color_map, set);
    out.base_color_texture = slots.assign(tex, set, out.base_color_map, at);
  }
  out.emission = emission(ctx, m, where);
  if (const json* t = member(m, "emissiveTexture")) {
    const std::string at = where + ".emissiveTexture";
    const int tex = textures.get(*t, at, true, out.emissive_map, set);
    out.emissive_texture = slots.assign(tex, set, out.emissive_map, at);
  }
  out.double_sided = bool_member(m, "doubleSided", false);
  out.alpha_mode = alpha_mode(ctx, m, where);
  out.alpha_cutoff = float(number_member(m, "alphaCutoff", 0.5));
  read_metallic_roughness(ctx, pbr, pw, textures, slots, out);
  read_specular(ctx, m, where, textures, slots, out);
  read_normal_map(ctx, m, where, textures, slots, out);
  uv = slots.sets();
  return out;
}

// A material no drawn primitive uses keeps its place in the list with its factors (read
// leniently: problems there are the validator's unused-part warning) and no textures.
Material placeholder(const json& m) {
  Material out;
  out.name = string_member(m, "name");
  const json* pbr = member(m, "pbrMetallicRoughness");
  const std::vector<double> base =
      pbr ? numbers_member(*pbr, "baseColorFactor") : std::vector<double>{};
  const std::vector<double> emissive = numbers_member(m, "emissiveFactor");
  for (int k = 0; k < 3; ++k) {
    if (base.size() == 4 && std::isfinite(base[std::size_t(k)]))
      out.base_color[k] = float(std::clamp(base[std::size_t(k)], 0.0, 1.0));
    if (emissive.size() == 3 && std::isfinite(emissive[std::size_t(k)]))
      out.emission[k] = float(std::max(emissive[std::size_t(k)], 0.0));
  }
  out.double_sided = bool_member(m, "doubleSided", false);
  return out;
}

} // namespace

void check_unused_images(const Context& ctx, const std::vector<char>& decoded) {
  const json& images = ctx.array("images");
  for (std::size_t i = 0; i < images.size(); ++i) {
    if (i < decoded.size() && decoded[i]) continue;
    const std::string pointer = pointer_of("images", i);
    const bool has_uri = member(images[i], "uri") != nullptr;
    try {
      if (has_uri && !member(images[i], "uri")->is_string()) continue; // the schema's issue
      if (!has_uri && !index_member(images[i], "bufferView")) continue;
      const std::vector<unsigned char> bytes = image_bytes(ctx, i);
      check_image_header(bytes.data(), bytes.size());
    } catch (const Error& e) {
      std::string what = e.what();
      const std::string prefix = ctx.file + ": " + element("images", i) + ": ";
      if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
      ctx.issues.add({pointer + (has_uri ? "/uri" : ""), "IO_ERROR", what});
    } catch (const ImageError& e) {
      ctx.issues.add({pointer, "IMAGE_DATA_INVALID", e.what()});
    }
  }
}

std::vector<UvSets> convert_materials(const Context& ctx, const std::vector<char>& referenced,
                                      Scene& scene, std::vector<char>& decoded_images) {
  decoded_images.assign(ctx.count("images"), 0);
  TextureTable textures(ctx, scene.textures, decoded_images);
  const json& materials = ctx.array("materials");
  std::vector<UvSets> uv(materials.size());
  for (std::size_t i = 0; i < materials.size(); ++i) {
    scene.materials.push_back(referenced[i] ? convert(ctx, i, textures, uv[i])
                                            : placeholder(materials[i]));
  }
  return uv;
}

} // namespace irad::gltf
