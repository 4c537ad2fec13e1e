#pragma once
// glTF 2.0 (.gltf and .glb) to irad::Scene through tinygltf 2.7.
// Supported: node hierarchy (TRS or matrix; normals by the inverse transpose), triangle
// primitives (indexed u8/u16/u32 or not), POSITION, NORMAL (flat normals when absent),
// TEXCOORD_0; materials (baseColorFactor, baseColorTexture decoded from sRGB, emissiveFactor x
// KHR_materials_emissive_strength, emissiveTexture, doubleSided); perspective cameras;
// KHR_lights_punctual point and spot lights. Only the default scene (or scene 0) is loaded.
// Every error throws irad::Error("FILE", "ELEMENT", "MESSAGE"), e.g. "box.gltf: accessors[3]: ...".
#include "core/log.h"
#include "core/scene.h"

#include <filesystem>

namespace irad {

Scene load_gltf(const std::filesystem::path& path, Log& log);

} // namespace irad
