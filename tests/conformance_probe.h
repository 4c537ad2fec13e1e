#pragma once
// The conformance test's probe: one emissive, double-sided triangle added to a glTF file, so that
// a file without geometry or light gets past "no triangles" / "no light" to the defect it holds.
//
// The probe never repairs what the file breaks. It returns nullopt (leave the file as it is) when
// the JSON does not parse exactly (syntax, a byte-order mark, duplicate keys, numbers that would
// not survive re-serialisation), the top level is not an object, an array the probe appends to
// (buffers, bufferViews, accessors, meshes, materials, nodes, scenes, the default scene's nodes)
// is present but not an array or is empty, the default scene cannot be found (`scene` out of
// range or not an index, the scene not an object), an index in the file equals the size of the
// array it refers to (the probe's element would resolve that dangling reference), or, for a GLB,
// the container is broken. Key order is kept.
// Everything else in the file (extensionsRequired included) is kept.
#include <optional>
#include <string>

namespace irad::test {

// A .gltf document's text with the triangle: a new data-URI buffer holding 3 float VEC3
// positions, its bufferView, an accessor with min/max, an emissive material (emissiveFactor
// [1, 1, 1], doubleSided), a mesh of one primitive, a node in the default scene (`scene`, else
// scenes[0]; a root anyway when there are no scenes). Existing arrays are appended to, absent
// ones created.
std::optional<std::string> probe_gltf_json(const std::string& text);

// A .glb file with the triangle added to its JSON chunk: the header's and the chunk's lengths are
// rewritten and the chunk padded with spaces to 4 bytes; every other chunk, and any bytes after
// the header's length, are kept unchanged. nullopt when the container is broken (header shorter
// than 12 bytes, bad magic, version other than 2, length beyond the file, first chunk not JSON,
// a chunk header or chunk beyond the length, a chunk length not a multiple of 4) or when
// probe_gltf_json refuses the JSON chunk.
std::optional<std::string> probe_glb(const std::string& bytes);

} // namespace irad::test
