#pragma once
// Internal to the glTF loader: materials and their textures.
#include "core/gltf/context.h"
#include "core/gltf/read/geometry.h"
#include "core/scene/scene.h"

namespace irad::gltf {

// Converts every material of the file, in file order, into scene.materials and the textures they
// use into scene.textures (decoded to linear, deduplicated by image, sampler and transfer
// function). Per material: base_color = baseColorFactor.rgb (each in [0, 1]; alpha ignored),
// emission = emissiveFactor (>= 0) x KHR_materials_emissive_strength.emissiveStrength (>= 0,
// default 1), doubleSided, metallicFactor, roughnessFactor and metallicRoughnessTexture,
// KHR_materials_ior, KHR_materials_specular (factor, colour, their textures), normalTexture with
// its scale (core/scene/scene.h Material; design.md 1b). Colour textures (base colour, emissive,
// specular colour) are sRGB-encoded in glTF and decoded here; the others are linear.
// occlusionTexture is not read (global illumination computes occlusion).
// Mirrors (seed section 5.1.2): a material is specular, a perfect mirror of reflectance
// base_color (x baseColorTexture), when metallicFactor >= mirror_min_metallic and roughnessFactor
// <= mirror_max_roughness.
inline constexpr double mirror_min_metallic = 0.9;
inline constexpr double mirror_max_roughness = 0.1;
// Materials no drawn primitive uses (referenced[i] == 0) are placeholders without textures.
// Returns, per material, the TEXCOORD sets of its two uv slots (Material::*_map.texcoord is the
// slot: a material whose textures read sets 0 and 2 gets TEXCOORD_0 in Scene::uvs and
// TEXCOORD_2 in Scene::uvs1; a texture reading a third set is dropped with a warning). Also read:
// alphaMode, alphaCutoff and baseColorFactor's alpha, KHR_texture_transform and texCoord of each
// textureInfo, EXT_texture_webp's source. Images no used texture decoded: each one's bytes are read
// and its header checked (no pixel is decoded); a problem is a validator issue of "/images/i" (so
// the one warning for unused parts counts it). `decoded[i]` marks the images the materials decoded.
void check_unused_images(const Context& ctx, const std::vector<char>& decoded);

std::vector<UvSets> convert_materials(const Context& ctx, const std::vector<char>& referenced,
                                      Scene& scene, std::vector<char>& decoded_images);

} // namespace irad::gltf
