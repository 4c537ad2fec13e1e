// The glTF 2.0 core JSON schema as tables (see validate_schema_internal.h). Definitions are in
// dependency order: an object type is defined before the types that contain it.
#include "core/gltf/validate/validate_schema_internal.h"

#include <array>

namespace irad::gltf::schema {
namespace {

// Building blocks.
constexpr Prop name_prop{.name = "name", .kind = Kind::String};

constexpr Prop numbers(std::string_view name, int length, double lo = -kInf, double hi = kInf) {
  return {.name = name,
          .kind = Kind::Array,
          .min = lo,
          .max = hi,
          .item = Kind::Number,
          .min_items = length,
          .max_items = length};
}
constexpr Prop collection(std::string_view name, const Schema* element) {
  return {.name = name,
          .kind = Kind::Array,
          .object = element,
          .item = Kind::Object,
          .min_items = 1,
          .collection = true};
}
constexpr Prop objects(std::string_view name, const Schema* element, bool required = false) {
  return {.name = name,
          .kind = Kind::Array,
          .required = required,
          .object = element,
          .item = Kind::Object,
          .min_items = 1};
}
constexpr Prop indices(std::string_view name, std::string_view target, bool required = false) {
  return {.name = name,
          .kind = Kind::Array,
          .required = required,
          .target = target,
          .item = Kind::Index,
          .min_items = 1,
          .unique = true};
}
constexpr Prop natural(std::string_view name, double lo = 0.0, bool required = false) {
  return {.name = name, .kind = Kind::Integer, .required = required, .min = lo};
}

// accessor
constexpr std::array sparse_indices_props{
    index("bufferView", "/bufferViews", true), natural("byteOffset"),
    Prop{.name = "componentType", .kind = Kind::Integer, .required = true}};
constexpr Schema sparse_indices{.location = "sparseIndices", .props = sparse_indices_props};
constexpr std::array sparse_values_props{index("bufferView", "/bufferViews", true),
                                         natural("byteOffset")};
constexpr Schema sparse_values{.location = "sparseValues", .props = sparse_values_props};
constexpr std::array sparse_props{
    natural("count", 1.0, true),
    Prop{.name = "indices", .kind = Kind::Object, .required = true, .object = &sparse_indices},
    Prop{.name = "values", .kind = Kind::Object, .required = true, .object = &sparse_values}};
constexpr Schema sparse{.location = "sparse", .props = sparse_props};
constexpr Prop bounds(std::string_view name) {
  return {.name = name, .kind = Kind::Array, .item = Kind::Number, .min_items = 1, .max_items = 16};
}
constexpr std::array accessor_props{
    index("bufferView", "/bufferViews"),
    natural("byteOffset"),
    Prop{.name = "componentType", .kind = Kind::Integer, .required = true},
    Prop{.name = "normalized", .kind = Kind::Bool},
    natural("count", 1.0, true),
    Prop{.name = "type", .kind = Kind::String, .required = true},
    bounds("max"),
    bounds("min"),
    Prop{.name = "sparse", .kind = Kind::Object, .object = &sparse},
    name_prop};
constexpr Schema accessor{.location = "accessor", .props = accessor_props, .rule = rule_accessor};

// animation
constexpr std::array target_props{index("node", "/nodes"),
                                  Prop{.name = "path", .kind = Kind::String, .required = true}};
constexpr Schema channel_target{
    .location = "channelTarget", .props = target_props, .rule = rule_channel_target};
constexpr std::array channel_props{
    index("sampler", "@samplers", true),
    Prop{.name = "target", .kind = Kind::Object, .required = true, .object = &channel_target}};
constexpr Schema channel{.location = "channel", .props = channel_props};
constexpr std::array anim_sampler_props{index("input", "/accessors", true),
                                        Prop{.name = "interpolation", .kind = Kind::String},
                                        index("output", "/accessors", true)};
constexpr Schema anim_sampler{.location = "animationSampler", .props = anim_sampler_props};
constexpr std::array animation_props{objects("channels", &channel, true),
                                     objects("samplers", &anim_sampler, true), name_prop};
constexpr Schema animation{
    .location = "animation", .props = animation_props, .scopes_samplers = true};

// asset
constexpr std::array asset_props{
    Prop{.name = "copyright", .kind = Kind::String},
    Prop{.name = "generator", .kind = Kind::String},
    Prop{.name = "version", .kind = Kind::String, .required = true, .pattern = Pattern::Version},
    Prop{.name = "minVersion", .kind = Kind::String, .pattern = Pattern::Version}};
constexpr Schema asset{.location = "asset", .props = asset_props, .rule = rule_asset};

// buffer, bufferView
constexpr std::array buffer_props{Prop{.name = "uri", .kind = Kind::String},
                                  natural("byteLength", 1.0, true), name_prop};
constexpr Schema buffer{.location = "buffer", .props = buffer_props, .rule = rule_buffer};
constexpr std::array buffer_view_props{
    index("buffer", "/buffers", true),
    natural("byteOffset"),
    natural("byteLength", 1.0, true),
    Prop{.name = "byteStride", .kind = Kind::Integer, .min = 4.0, .max = 252.0, .multiple_of = 4},
    Prop{.name = "target", .kind = Kind::Integer},
    name_prop};
constexpr Schema buffer_view{.location = "bufferView", .props = buffer_view_props};

// camera
constexpr std::array orthographic_props{
    Prop{.name = "xmag", .kind = Kind::Number, .required = true},
    Prop{.name = "ymag", .kind = Kind::Number, .required = true},
    Prop{.name = "zfar", .kind = Kind::Number, .required = true, .min = 0.0, .min_excl = true},
    Prop{.name = "znear", .kind = Kind::Number, .required = true, .min = 0.0}};
constexpr Schema orthographic{
    .location = "orthographic", .props = orthographic_props, .rule = rule_orthographic};
constexpr Prop positive(std::string_view name, bool required = false) {
  return {.name = name, .kind = Kind::Number, .required = required, .min = 0.0, .min_excl = true};
}
constexpr std::array perspective_props{positive("aspectRatio"), positive("yfov", true),
                                       positive("zfar"), positive("znear", true)};
constexpr Schema perspective{
    .location = "perspective", .props = perspective_props, .rule = rule_perspective};
constexpr std::array camera_props{
    Prop{.name = "orthographic", .kind = Kind::Object, .object = &orthographic},
    Prop{.name = "perspective", .kind = Kind::Object, .object = &perspective},
    Prop{.name = "type", .kind = Kind::String, .required = true}, name_prop};
constexpr Schema camera{.location = "camera", .props = camera_props, .rule = rule_camera};

// image
constexpr std::array image_props{Prop{.name = "uri", .kind = Kind::String},
                                 Prop{.name = "mimeType", .kind = Kind::String},
                                 index("bufferView", "/bufferViews"), name_prop};
constexpr Schema image{.location = "image", .props = image_props, .rule = rule_image};

} // namespace

// Texture references (shared with the extensions' tables).
constexpr std::array texture_info_props{index("index", "/textures", true), natural("texCoord")};
const Schema kTextureInfo{.location = "textureInfo", .props = texture_info_props};
constexpr std::array normal_info_props{index("index", "/textures", true), natural("texCoord"),
                                       Prop{.name = "scale", .kind = Kind::Number}};
const Schema kNormalTextureInfo{.location = "textureInfo", .props = normal_info_props};

namespace {

constexpr std::array occlusion_info_props{index("index", "/textures", true), natural("texCoord"),
                                          unit("strength")};
constexpr Schema occlusion_info{.location = "textureInfo", .props = occlusion_info_props};

// material
constexpr std::array pbr_props{numbers("baseColorFactor", 4, 0.0, 1.0), texture("baseColorTexture"),
                               unit("metallicFactor"), unit("roughnessFactor"),
                               texture("metallicRoughnessTexture")};
constexpr Schema pbr{.location = "pbrMetallicRoughness", .props = pbr_props};
constexpr std::array material_props{
    name_prop,
    Prop{.name = "pbrMetallicRoughness", .kind = Kind::Object, .object = &pbr},
    Prop{.name = "normalTexture", .kind = Kind::Object, .object = &kNormalTextureInfo},
    Prop{.name = "occlusionTexture", .kind = Kind::Object, .object = &occlusion_info},
    texture("emissiveTexture"),
    numbers("emissiveFactor", 3, 0.0, 1.0),
    Prop{.name = "alphaMode", .kind = Kind::String},
    Prop{.name = "alphaCutoff", .kind = Kind::Number, .min = 0.0},
    Prop{.name = "doubleSided", .kind = Kind::Bool}};
constexpr Schema material{.location = "material", .props = material_props};

// mesh
constexpr Prop accessor_ref = index("", "/accessors");
constexpr Schema attributes{.location = "attributes", .each = &accessor_ref, .min_members = 1};
constexpr Schema morph_target{.location = "target", .each = &accessor_ref, .min_members = 1};
constexpr std::array primitive_props{
    Prop{.name = "attributes", .kind = Kind::Object, .required = true, .object = &attributes},
    index("indices", "/accessors"), index("material", "/materials"),
    Prop{.name = "mode", .kind = Kind::Integer}, objects("targets", &morph_target)};
constexpr Schema primitive{.location = "primitive", .props = primitive_props};
constexpr std::array mesh_props{
    objects("primitives", &primitive, true),
    Prop{.name = "weights", .kind = Kind::Array, .item = Kind::Number, .min_items = 1}, name_prop};
constexpr Schema mesh{.location = "mesh", .props = mesh_props};

// node
constexpr std::array node_props{
    index("camera", "/cameras"),
    indices("children", "/nodes"),
    index("skin", "/skins"),
    numbers("matrix", 16),
    index("mesh", "/meshes"),
    numbers("rotation", 4, -1.0, 1.0),
    numbers("scale", 3),
    numbers("translation", 3),
    Prop{.name = "weights", .kind = Kind::Array, .item = Kind::Number, .min_items = 1},
    name_prop};
constexpr Schema node{.location = "node", .props = node_props, .rule = rule_node};

// sampler, scene, skin, texture
constexpr std::array sampler_props{Prop{.name = "magFilter", .kind = Kind::Integer},
                                   Prop{.name = "minFilter", .kind = Kind::Integer},
                                   Prop{.name = "wrapS", .kind = Kind::Integer},
                                   Prop{.name = "wrapT", .kind = Kind::Integer}, name_prop};
constexpr Schema sampler{.location = "sampler", .props = sampler_props};
constexpr std::array scene_props{indices("nodes", "/nodes"), name_prop};
constexpr Schema scene{.location = "scene", .props = scene_props};
constexpr std::array skin_props{index("inverseBindMatrices", "/accessors"),
                                index("skeleton", "/nodes"), indices("joints", "/nodes", true),
                                name_prop};
constexpr Schema skin{.location = "skin", .props = skin_props};
constexpr std::array texture_props{index("sampler", "/samplers"), index("source", "/images"),
                                   name_prop};
constexpr Schema texture_schema{
    .location = "texture", .props = texture_props, .rule = rule_texture};

// The document.
constexpr Prop extension_names(std::string_view name) {
  return {.name = name, .kind = Kind::Array, .item = Kind::String, .min_items = 1, .unique = true};
}
constexpr std::array root_props{
    extension_names("extensionsUsed"),
    extension_names("extensionsRequired"),
    collection("accessors", &accessor),
    collection("animations", &animation),
    Prop{.name = "asset", .kind = Kind::Object, .required = true, .object = &asset},
    collection("buffers", &buffer),
    collection("bufferViews", &buffer_view),
    collection("cameras", &camera),
    collection("images", &image),
    collection("materials", &material),
    collection("meshes", &mesh),
    collection("nodes", &node),
    collection("samplers", &sampler),
    index("scene", "/scenes"),
    collection("scenes", &scene),
    collection("skins", &skin),
    collection("textures", &texture_schema)};

} // namespace

const Schema kRoot{.location = "root", .props = root_props, .rule = rule_root};

} // namespace irad::gltf::schema
