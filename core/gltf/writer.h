#pragma once
// irad::Scene to glTF 2.0 (.gltf): one JSON file whose single binary buffer is embedded as a
// base64 data URI, written with nlohmann::json. load_gltf (core/gltf/loader.h) reads it back to
// the same triangles, materials, cameras and punctual lights, up to float rounding of the camera
// and light frames.
//
// What is written:
// - one mesh (in one node without transform) with one triangle primitive per material that has
//   triangles, in material order, each triangle keeping its scene order within its primitive;
//   per primitive the vertices it uses: POSITION (float VEC3, with min/max), NORMAL (float
//   VEC3), TEXCOORD_0 (float VEC2) when the scene has uvs, and unsigned 32-bit indices;
// - every material: name, pbrMetallicRoughness.baseColorFactor = (albedo, 1), metallicFactor and
//   roughnessFactor (a mirror, Material::specular: 1 and 0), KHR_materials_specular's factor and
//   colour where they differ from 1 (a Lambertian material: specularFactor 0), KHR_materials_ior
//   where ior differs from 1.5, doubleSided, and the emission as emissiveFactor; when a component
//   exceeds 1 the factor is divided by the largest component, which becomes
//   KHR_materials_emissive_strength.emissiveStrength (listed in extensionsUsed);
// - every camera: perspective, yfov, aspectRatio when set, zfar when set, and znear = the
//   camera's znear when positive, else the near plane make_view (core/camera/view.h) fits for this
//   scene (glTF requires znear > 0; loaded back, make_view then gives the same near plane); placed
//   by a node whose matrix is camera_to_world;
// - every punctual light as KHR_lights_punctual point or spot light: intensity = the largest
//   component of the radiant intensity, color = intensity / that (white when zero); placed by a
//   node whose matrix maps the light's -z axis to its direction.
// Not written: textures and images (every texture of a material is dropped, so a textured scene
// comes back untextured), tangents, Scene::source.
//
// The file is written to FILE.tmp and renamed over FILE, so FILE is either complete or untouched.
// Errors throw irad::Error naming the file: a missing output folder, a failed write, or a scene
// the loader would reject (non-finite positions, albedo outside [0, 1], negative emission).
#include "core/scene/scene.h"

#include <filesystem>

namespace irad {

void write_gltf(const Scene& scene, const std::filesystem::path& path);

} // namespace irad
