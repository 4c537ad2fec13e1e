#pragma once
// Internal to the glTF loader: the checks of the Khronos glTF-Validator that concern a
// document's JSON and its buffers' data, each problem reported as an Issue with the JSON pointer
// of the element it concerns. The loader decides what an issue means (core/gltf/issue_book.h): an
// error when irad uses the element, a repaired value, a warning when it concerns only an
// extension irad ignores, or one warning line for the unused rest.
#include <cstddef>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace irad::gltf {

struct Issue {
  std::string pointer; // JSON pointer, e.g. "/meshes/2/primitives/0/attributes/NORMAL"
  std::string code;    // the validator's code, e.g. "MESH_PRIMITIVE_UNEQUAL_ACCESSOR_COUNT"
  std::string message; // irad's own words, one line, without the pointer
  // The extensions whose content alone raises an issue that lies outside them (e.g.
  // MESH_PRIMITIVE_NO_TANGENT_SPACE at a primitive's material, raised by the material's
  // KHR_materials_clearcoat): without all of them the issue does not arise. Empty when the core
  // document raises it; an issue inside an extension's object is known by its pointer instead.
  std::vector<std::string> extensions = {};
};

// The bytes of buffer i as the loader resolved them (GLB BIN chunk, data URI or external file);
// present == false when the buffer has no data (no uri outside a GLB, or not loaded).
struct BufferBytes {
  const unsigned char* data = nullptr;
  std::size_t size = 0;
  bool present = false;
  // Set by the caller on buffer 0 of a GLB file that has no BIN chunk (BUFFER_MISSING_GLB_DATA
  // when that buffer has no uri); a .gltf file's uri-less buffer is not an error by itself.
  bool glb_without_bin = false;
};

// Every error-severity problem the glTF-Validator would report for this document (schema: types,
// required properties, ranges, enums, empty entities, unresolved references, declared
// extensions; semantics: accessor and bufferView layout, accessor data against min/max and
// index ranges, mesh attributes, node hierarchy and transforms, skins, animations, cameras,
// textures and images, extension objects irad knows). Never throws on any JSON value; buffers
// may be shorter than declared. Issues are in document order.
std::vector<Issue> validate(const nlohmann::json& root, const std::vector<BufferBytes>& buffers);

} // namespace irad::gltf
