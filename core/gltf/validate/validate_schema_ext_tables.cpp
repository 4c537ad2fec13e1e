// The JSON schemas of the glTF extensions irad's validator knows, as tables (see
// validate_schema_internal.h), and where each extension's objects may appear.
#include "core/gltf/validate/validate_schema_internal.h"

#include <array>
#include <numbers>

namespace irad::gltf::schema {
namespace {

constexpr Prop at_least(std::string_view name, double lo) {
  return {.name = name, .kind = Kind::Number, .min = lo};
}
constexpr Prop color(std::string_view name, double hi = 1.0) {
  return {.name = name,
          .kind = Kind::Array,
          .min = 0.0,
          .max = hi,
          .item = Kind::Number,
          .min_items = 3,
          .max_items = 3};
}

// KHR_lights_punctual
constexpr std::array spot_props{Prop{.name = "innerConeAngle",
                                     .kind = Kind::Number,
                                     .min = 0.0,
                                     .max = std::numbers::pi / 2.0,
                                     .max_excl = true},
                                Prop{.name = "outerConeAngle",
                                     .kind = Kind::Number,
                                     .min = 0.0,
                                     .max = std::numbers::pi / 2.0,
                                     .min_excl = true}};
constexpr Schema spot{.location = "spot", .props = spot_props};
constexpr std::array light_props{
    color("color"),
    at_least("intensity", 0.0),
    Prop{.name = "spot", .kind = Kind::Object, .object = &spot},
    Prop{.name = "type", .kind = Kind::String, .required = true},
    Prop{.name = "range", .kind = Kind::Number, .min = 0.0, .min_excl = true},
    Prop{.name = "name", .kind = Kind::String}};
constexpr Schema light{.location = "light", .props = light_props, .rule = rule_light};
constexpr std::array lights_root_props{Prop{.name = "lights",
                                            .kind = Kind::Array,
                                            .required = true,
                                            .object = &light,
                                            .item = Kind::Object,
                                            .min_items = 1}};
constexpr Schema lights_root{.props = lights_root_props};
constexpr std::array lights_node_props{
    index("light", "/extensions/KHR_lights_punctual/lights", true)};
constexpr Schema lights_node{.props = lights_node_props, .rule = rule_node_light};

// KHR_materials_variants
constexpr std::array variant_props{Prop{.name = "name", .kind = Kind::String, .required = true}};
constexpr Schema variant{.props = variant_props};
constexpr std::array variants_root_props{Prop{.name = "variants",
                                              .kind = Kind::Array,
                                              .required = true,
                                              .object = &variant,
                                              .item = Kind::Object,
                                              .min_items = 1}};
constexpr Schema variants_root{.props = variants_root_props};
constexpr std::array mapping_props{Prop{.name = "variants",
                                        .kind = Kind::Array,
                                        .required = true,
                                        .target = "/extensions/KHR_materials_variants/variants",
                                        .item = Kind::Index,
                                        .min_items = 1,
                                        .unique = true},
                                   index("material", "/materials", true),
                                   Prop{.name = "name", .kind = Kind::String}};
constexpr Schema mapping{.props = mapping_props};
constexpr std::array variants_primitive_props{Prop{.name = "mappings",
                                                   .kind = Kind::Array,
                                                   .required = true,
                                                   .object = &mapping,
                                                   .item = Kind::Object,
                                                   .min_items = 1}};
constexpr Schema variants_primitive{.props = variants_primitive_props,
                                    .rule = rule_primitive_variants};

// KHR_animation_pointer
constexpr std::array pointer_props{Prop{
    .name = "pointer", .kind = Kind::String, .required = true, .pattern = Pattern::JsonPointer}};
constexpr Schema pointer_target{.props = pointer_props};

// Texture extensions.
constexpr std::array transform_props{
    Prop{.name = "offset",
         .kind = Kind::Array,
         .item = Kind::Number,
         .min_items = 2,
         .max_items = 2},
    Prop{.name = "rotation", .kind = Kind::Number},
    Prop{
        .name = "scale", .kind = Kind::Array, .item = Kind::Number, .min_items = 2, .max_items = 2},
    Prop{.name = "texCoord", .kind = Kind::Integer, .min = 0.0}};
constexpr Schema transform{.props = transform_props};
constexpr std::array source_props{index("source", "/images")};
constexpr Schema texture_source{.props = source_props};
constexpr std::array visibility_props{Prop{.name = "visible", .kind = Kind::Bool}};
constexpr Schema visibility{.props = visibility_props};

// KHR_materials_*
constexpr std::array anisotropy_props{unit("anisotropyStrength"),
                                      Prop{.name = "anisotropyRotation", .kind = Kind::Number},
                                      texture("anisotropyTexture")};
constexpr Schema anisotropy{.props = anisotropy_props};
constexpr std::array clearcoat_props{
    unit("clearcoatFactor"), texture("clearcoatTexture"), unit("clearcoatRoughnessFactor"),
    texture("clearcoatRoughnessTexture"),
    Prop{.name = "clearcoatNormalTexture", .kind = Kind::Object, .object = &kNormalTextureInfo}};
constexpr Schema clearcoat{.props = clearcoat_props};
constexpr std::array dispersion_props{at_least("dispersion", 0.0)};
constexpr Schema dispersion{.props = dispersion_props};
constexpr std::array emissive_props{at_least("emissiveStrength", 0.0)};
constexpr Schema emissive_strength{.props = emissive_props};
constexpr std::array ior_props{at_least("ior", 0.0)};
constexpr Schema ior{.props = ior_props, .rule = rule_ior};
constexpr std::array iridescence_props{unit("iridescenceFactor"),
                                       texture("iridescenceTexture"),
                                       at_least("iridescenceIor", 1.0),
                                       at_least("iridescenceThicknessMinimum", 0.0),
                                       at_least("iridescenceThicknessMaximum", 0.0),
                                       texture("iridescenceThicknessTexture")};
constexpr Schema iridescence{.props = iridescence_props};
constexpr std::array spec_gloss_props{Prop{.name = "diffuseFactor",
                                           .kind = Kind::Array,
                                           .min = 0.0,
                                           .max = 1.0,
                                           .item = Kind::Number,
                                           .min_items = 4,
                                           .max_items = 4},
                                      texture("diffuseTexture"), color("specularFactor"),
                                      unit("glossinessFactor"),
                                      texture("specularGlossinessTexture")};
constexpr Schema spec_gloss{.props = spec_gloss_props};
constexpr std::array sheen_props{color("sheenColorFactor"), texture("sheenColorTexture"),
                                 unit("sheenRoughnessFactor"), texture("sheenRoughnessTexture")};
constexpr Schema sheen{.props = sheen_props};
constexpr std::array specular_props{unit("specularFactor"), texture("specularTexture"),
                                    color("specularColorFactor", kInf),
                                    texture("specularColorTexture")};
constexpr Schema specular{.props = specular_props};
constexpr std::array transmission_props{unit("transmissionFactor"), texture("transmissionTexture")};
constexpr Schema transmission{.props = transmission_props};
constexpr Schema unlit{};
constexpr std::array volume_props{
    at_least("thicknessFactor", 0.0), texture("thicknessTexture"),
    Prop{.name = "attenuationDistance", .kind = Kind::Number, .min = 0.0, .min_excl = true},
    color("attenuationColor")};
constexpr Schema volume{.props = volume_props};

constexpr std::array<Extension, 27> table{{
    {"KHR_lights_punctual", "root", &lights_root},
    {"KHR_lights_punctual", "node", &lights_node},
    {"KHR_materials_variants", "root", &variants_root},
    {"KHR_materials_variants", "primitive", &variants_primitive},
    {"KHR_animation_pointer", "channelTarget", &pointer_target},
    {"KHR_texture_transform", "textureInfo", &transform},
    {"EXT_texture_webp", "texture", &texture_source},
    {"KHR_texture_basisu", "texture", &texture_source},
    {"KHR_node_visibility", "node", &visibility},
    {"KHR_mesh_quantization", "", nullptr},
    {"KHR_materials_anisotropy", "material", &anisotropy},
    {"KHR_materials_clearcoat", "material", &clearcoat},
    {"KHR_materials_dispersion", "material", &dispersion},
    {"KHR_materials_emissive_strength", "material", &emissive_strength},
    {"KHR_materials_ior", "material", &ior},
    {"KHR_materials_iridescence", "material", &iridescence},
    {"KHR_materials_pbrSpecularGlossiness", "material", &spec_gloss},
    {"KHR_materials_sheen", "material", &sheen},
    {"KHR_materials_specular", "material", &specular},
    {"KHR_materials_transmission", "material", &transmission},
    {"KHR_materials_unlit", "material", &unlit},
    {"KHR_materials_volume", "material", &volume},
    {"KHR_draco_mesh_compression", "primitive", nullptr},
    {"EXT_meshopt_compression", "bufferView", nullptr},
    {"EXT_meshopt_compression", "buffer", nullptr},
    {"EXT_mesh_gpu_instancing", "node", nullptr},
    {"KHR_materials_diffuse_transmission", "material", nullptr},
}};

} // namespace

std::span<const Extension> extensions() {
  return table;
}

} // namespace irad::gltf::schema
