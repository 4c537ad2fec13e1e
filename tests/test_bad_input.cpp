// Every bad input of docs/errors.md, each with its exact message: through the library (one
// irad::Error "FILE: ELEMENT: MESSAGE") and through the real command line (exit code 1, the one
// line "irad: error: FILE: ELEMENT: MESSAGE" on stderr, no output file).
#include "core/gltf/loader.h"
#include "core/util/error.h"
#include "core/util/log.h"
#include "tests/gltf_test_scene.h"
#include "tests/test_paths.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <gtest/gtest.h>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace IRAD_UNITY_ID {

using namespace gltf_test;

// GLB bytes from a JSON text and an optional BIN payload, with header fields that can be spoiled.
struct Glb {
  std::string json_text = R"({"asset":{"version":"2.0"}})";
  std::vector<unsigned char> bin;
  std::uint32_t magic = 0x46546C67;
  std::uint32_t version = 2;
  std::int64_t length_delta = 0;     // added to the header's length
  std::int64_t bin_length_delta = 0; // added to the BIN chunk's length field
  std::uint32_t first_type = 0x4E4F534A;
  bool pad_json = true;                // to a multiple of 4 bytes
  std::vector<unsigned char> trailing; // after the chunks, counted in the length

  std::vector<unsigned char> bytes() const {
    std::string text = json_text;
    while (pad_json && text.size() % 4 != 0) text += ' ';
    std::vector<unsigned char> body = bin;
    while (body.size() % 4 != 0) body.push_back(0);
    std::vector<unsigned char> chunks;
    put_le32(chunks, static_cast<std::uint32_t>(text.size()));
    put_le32(chunks, first_type);
    chunks.insert(chunks.end(), text.begin(), text.end());
    if (!body.empty()) {
      put_le32(chunks, static_cast<std::uint32_t>(std::int64_t(body.size()) + bin_length_delta));
      put_le32(chunks, 0x004E4942u);
      chunks.insert(chunks.end(), body.begin(), body.end());
    }
    chunks.insert(chunks.end(), trailing.begin(), trailing.end());
    std::vector<unsigned char> out;
    put_le32(out, magic);
    put_le32(out, version);
    put_le32(out, static_cast<std::uint32_t>(std::int64_t(12 + chunks.size()) + length_delta));
    out.insert(out.end(), chunks.begin(), chunks.end());
    return out;
  }
  fs::path write(const fs::path& path) const {
    const std::vector<unsigned char> b = bytes();
    write_file(path, b.data(), b.size());
    return path;
  }
};

// The emissive quad with its JSON spoiled by `spoil`, written as NAME (.gltf, data URI buffer).
fs::path quad(const fs::path& dir, const std::string& name,
              const std::function<void(Gltf&)>& spoil) {
  Gltf g = emissive_quad();
  spoil(g);
  return g.write_gltf(dir / name);
}

// The emissive quad written as NAME with its buffers[0] replaced by `buffer` (the bytes stay in
// `bin`: for data URIs of any content).
fs::path quad_buffer(const fs::path& dir, const std::string& name, const json& buffer) {
  Gltf g = emissive_quad();
  json d = g.doc;
  d["buffers"] = json::array({buffer});
  write_file(dir / name, d.dump());
  return dir / name;
}

// The emissive quad as a GLB whose buffers[0] is `buffer` and whose BIN chunk holds `bin` (no
// BIN chunk when empty).
Glb quad_glb(const json& buffer, const std::vector<unsigned char>& bin) {
  json d = emissive_quad().doc;
  d["buffers"] = json::array({buffer});
  Glb glb;
  glb.json_text = d.dump();
  glb.bin = bin;
  return glb;
}

std::string data_uri(const std::vector<unsigned char>& bytes) {
  return "data:application/octet-stream;base64," + base64(bytes);
}

// The quad with a base colour texture whose image is `image` (a JSON images[0]).
fs::path textured_quad(const fs::path& dir, const std::string& name, const json& image) {
  Gltf g = emissive_quad();
  g.push("images", image);
  g.push("textures", {{"source", 0}});
  g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 0;
  return g.write_gltf(dir / name);
}

std::vector<unsigned char> grey_png(int w, int h) {
  return png(w, h, 1, 8, std::vector<std::uint16_t>(std::size_t(w * h), 128));
}

struct Case {
  const char* name;
  std::function<fs::path(const fs::path& dir)> make;
  std::string message;       // what() after "FILE: "
  irad::LoadLimits limits{}; // for the library
  std::string cli_options{}; // the same limits for the command line
};

irad::LoadLimits limits(const std::function<void(irad::LoadLimits&)>& set) {
  irad::LoadLimits l;
  set(l);
  return l;
}

std::vector<Case> cases() {
  const std::vector<unsigned char> bin = emissive_quad().bin; // 108 bytes
  std::vector<Case> c;
  // The file.
  c.push_back({"not_found", [](const fs::path& d) { return d / "missing.gltf"; },
               "cannot open file: No such file or directory"});
  c.push_back({"directory",
               [](const fs::path& d) {
                 fs::create_directories(d / "folder.gltf");
                 return d / "folder.gltf";
               },
               "cannot open file: is a directory"});
  c.push_back({"empty",
               [](const fs::path& d) {
                 write_file(d / "empty.gltf", "");
                 return d / "empty.gltf";
               },
               "empty file"});
  c.push_back({"file_over_limit",
               [](const fs::path& d) {
                 write_file(d / "big.gltf", std::string(1536 * 1024, ' '));
                 return d / "big.gltf";
               },
               "file larger than the limit of 1048576 bytes (--max-file-size)",
               limits([](irad::LoadLimits& l) { l.max_file_bytes = 1 << 20; }),
               "--max-file-size 1"});
  c.push_back({"not_json",
               [](const fs::path& d) {
                 write_file(d / "text.gltf", "hello");
                 return d / "text.gltf";
               },
               "JSON: not valid JSON: parse error at line 1, column 1: syntax error while "
               "parsing value - invalid literal; last read: 'h'"});
  c.push_back({"truncated_json",
               [](const fs::path& d) {
                 write_file(d / "cut.gltf", R"({"asset": {"version": "2.0"}, "nodes": [{"me)");
                 return d / "cut.gltf";
               },
               "JSON: not valid JSON: parse error at line 1, column 45: syntax error while "
               "parsing object key - invalid string: missing closing quote; last read: "
               "'\"me'; expected string literal"});
  c.push_back({"json_not_object",
               [](const fs::path& d) {
                 write_file(d / "array.gltf", "[1, 2]");
                 return d / "array.gltf";
               },
               "JSON: the top level is not an object"});
  c.push_back({"json_too_deep",
               [](const fs::path& d) {
                 write_file(d / "deep.gltf", R"({"asset":{"version":"2.0"},"extras":)" +
                                                 std::string(100, '[') + std::string(100, ']') +
                                                 "}");
                 return d / "deep.gltf";
               },
               "JSON: nested deeper than the limit of 64 levels"});
  c.push_back({"no_asset",
               [](const fs::path& d) {
                 write_file(d / "noasset.gltf", R"({"scenes": []})");
                 return d / "noasset.gltf";
               },
               "asset: missing (required)"});
  c.push_back({"wrong_version",
               [](const fs::path& d) {
                 return quad(d, "v1.gltf", [](Gltf& g) { g.doc["asset"]["version"] = "1.0"; });
               },
               "asset.version: unsupported glTF version '1.0'"});
  // GLB.
  c.push_back({"glb_truncated_header",
               [](const fs::path& d) {
                 write_file(d / "short.glb", std::string("glTF\x02\0\0\0", 8));
                 return d / "short.glb";
               },
               "GLB header: truncated: 8 bytes, 12 needed"});
  c.push_back({"glb_bad_magic",
               [](const fs::path& d) { return emissive_quad().write_glb(d / "magic.glb", "glTX"); },
               "GLB header: bad magic 'glTX' (expected 'glTF')"});
  c.push_back({"glb_version",
               [](const fs::path& d) {
                 Glb g;
                 g.version = 1;
                 return g.write(d / "v1.glb");
               },
               "GLB header: unsupported GLB version 1 (must be 2)"});
  c.push_back({"glb_length_beyond_file",
               [](const fs::path& d) {
                 Glb g;
                 g.length_delta = 100;
                 return g.write(d / "length.glb");
               },
               "GLB header: length 148 exceeds the file's 48 bytes (truncated)"});
  c.push_back({"glb_chunk_beyond_file",
               [bin](const fs::path& d) {
                 Glb g;
                 g.bin = bin;
                 g.bin_length_delta = 4;
                 return g.write(d / "chunk.glb");
               },
               "GLB chunks[1]: chunk length 112 exceeds the 108 bytes left in the file"});
  c.push_back({"glb_first_chunk_not_json",
               [](const fs::path& d) {
                 Glb g;
                 g.first_type = 0x004E4942u;
                 return g.write(d / "first.glb");
               },
               "GLB chunks[0]: the first chunk must be JSON, got type 0x004e4942"});
  c.push_back({"glb_chunk_header_truncated",
               [](const fs::path& d) {
                 Glb g;
                 g.trailing = {1, 2, 3, 4};
                 return g.write(d / "header.glb");
               },
               "GLB chunks[1]: truncated chunk header: 4 bytes left, 8 needed"});
  c.push_back({"glb_chunk_not_multiple_of_4",
               [](const fs::path& d) {
                 Glb g;
                 g.json_text = R"({"asset":{"version":"2.0"}})"; // 27 bytes
                 g.pad_json = false;
                 return g.write(d / "unaligned.glb");
               },
               "GLB chunks[0]: chunk length 27 is not a multiple of 4"});
  c.push_back({"glb_second_json_chunk",
               [](const fs::path& d) {
                 Glb g;
                 g.trailing = {0, 0, 0, 0, 'J', 'S', 'O', 'N'};
                 return g.write(d / "twice.glb");
               },
               "GLB chunks[1]: more than one JSON or BIN chunk"});
  // The buffer must be used (by the quad's accessors): a problem in an unused buffer is only
  // counted in the one warning about unused elements.
  c.push_back({"glb_no_bin_chunk",
               [bin](const fs::path& d) {
                 return quad_glb({{"byteLength", bin.size()}}, {}).write(d / "nobin.glb");
               },
               "buffers[0]: buffer 0 has no uri and the GLB has no BIN chunk"});
  c.push_back({"glb_bin_shorter_than_byte_length",
               [bin](const fs::path& d) {
                 return quad_glb({{"byteLength", bin.size() + 16}}, bin).write(d / "binshort.glb");
               },
               "buffers[0]: the buffer has 108 bytes, fewer than its byteLength 124"});
  // Buffers.
  c.push_back({"buffer_index_out_of_range",
               [](const fs::path& d) {
                 return quad(d, "buffer.gltf",
                             [](Gltf& g) { g.doc["bufferViews"][0]["buffer"] = 3; });
               },
               "bufferViews[0].buffer: index 3 refers to nothing"});
  c.push_back({"no_buffers",
               [](const fs::path& d) {
                 Gltf g = emissive_quad();
                 write_file(d / "nobuffers.gltf", g.doc.dump());
                 return d / "nobuffers.gltf";
               },
               "bufferViews[0].buffer: index 0 refers to nothing"});
  c.push_back({"data_uri_not_base64",
               [bin](const fs::path& d) {
                 std::string uri = data_uri(bin);
                 uri[40] = '*';
                 return quad_buffer(d, "b64.gltf", {{"byteLength", bin.size()}, {"uri", uri}});
               },
               "buffers[0]: data URI is not valid base64 (character 4 of the data)"});
  c.push_back({"data_uri_media_type",
               [bin](const fs::path& d) {
                 return quad_buffer(d, "media.gltf",
                                    {{"byteLength", bin.size()},
                                     {"uri", "data:text/plain;base64," + base64(bin)}});
               },
               "buffers[0]: unsupported data URI 'data:text/plain;base64' (expected base64 data of "
               "type application/octet-stream, application/gltf-buffer)"});
  c.push_back({"data_uri_shorter_than_byte_length",
               [bin](const fs::path& d) {
                 return quad_buffer(d, "short.gltf",
                                    {{"byteLength", bin.size() + 16}, {"uri", data_uri(bin)}});
               },
               "buffers[0]: its data hold 108 bytes, byteLength says 124"});
  c.push_back({"data_uri_longer_than_byte_length",
               [bin](const fs::path& d) {
                 return quad_buffer(d, "long.gltf",
                                    {{"byteLength", bin.size() - 8}, {"uri", data_uri(bin)}});
               },
               "buffers[0]: its data hold 108 bytes, byteLength says 100"});
  c.push_back(
      {"external_buffer_missing",
       [bin](const fs::path& d) {
         return quad_buffer(d, "nobin.gltf", {{"byteLength", bin.size()}, {"uri", "nobin.bin"}});
       },
       "buffers[0]: external file 'nobin.bin' not found"});
  c.push_back({"external_buffer_shorter",
               [bin](const fs::path& d) {
                 const fs::path p = emissive_quad().write_gltf_bin(d / "short_bin.gltf");
                 fs::resize_file(d / "short_bin.bin", bin.size() - 8);
                 return p;
               },
               "buffers[0]: its data hold 100 bytes, byteLength says 108"});
  c.push_back({"uri_leaves_folder",
               [bin](const fs::path& d) {
                 fs::create_directories(d / "sub");
                 write_file(d / "quad.bin", bin.data(), bin.size());
                 return quad_buffer(d / "sub", "up.gltf",
                                    {{"byteLength", bin.size()}, {"uri", "../quad.bin"}});
               },
               "buffers[0]: uri '../quad.bin' leaves the scene's folder ('..')"});
  c.push_back({"uri_percent_encoded_dots",
               [bin](const fs::path& d) {
                 return quad_buffer(d, "encoded.gltf",
                                    {{"byteLength", bin.size()}, {"uri", "a/%2e%2e/%2E%2E/x.bin"}});
               },
               "buffers[0]: uri 'a/%2e%2e/%2E%2E/x.bin' leaves the scene's folder ('..')"});
  c.push_back(
      {"uri_absolute",
       [bin](const fs::path& d) {
         return quad_buffer(d, "abs.gltf", {{"byteLength", bin.size()}, {"uri", "/etc/passwd"}});
       },
       "buffers[0]: uri '/etc/passwd' is an absolute path (external files must lie in "
       "the scene's folder)"});
  c.push_back(
      {"external_buffer_over_limit",
       [](const fs::path& d) {
         write_file(d / "big.bin", std::string(1536 * 1024, '\0'));
         return quad_buffer(d, "bigbin.gltf", {{"byteLength", 1536 * 1024}, {"uri", "big.bin"}});
       },
       "buffers[0]: file larger than the limit of 1048576 bytes (--max-file-size)",
       limits([](irad::LoadLimits& l) { l.max_file_bytes = 1 << 20; }), "--max-file-size 1"});
  c.push_back({"buffer_byte_length_zero",
               [](const fs::path& d) {
                 return quad_buffer(d, "zero.gltf", {{"byteLength", 0}, {"uri", "x.bin"}});
               },
               "buffers[0]: external file 'x.bin' not found"});
  // Views and accessors.
  c.push_back({"negative_view_offset",
               [](const fs::path& d) {
                 return quad(d, "negview.gltf",
                             [](Gltf& g) { g.doc["bufferViews"][1]["byteOffset"] = -4; });
               },
               "bufferViews[1].byteOffset: value -4 is out of range"});
  c.push_back({"negative_accessor_offset",
               [](const fs::path& d) {
                 return quad(d, "negacc.gltf",
                             [](Gltf& g) { g.doc["accessors"][0]["byteOffset"] = -12; });
               },
               "accessors[0].byteOffset: value -12 is out of range"});
  c.push_back({"view_beyond_buffer",
               [](const fs::path& d) {
                 return quad(d, "view.gltf",
                             [](Gltf& g) { g.doc["bufferViews"][0]["byteLength"] = 4096; });
               },
               "bufferViews[0].byteLength: the view ends past the end of its buffer"});
  c.push_back({"accessor_beyond_view",
               [](const fs::path& d) {
                 return quad(d, "acc.gltf",
                             [](Gltf& g) { g.doc["accessors"][0]["byteOffset"] = 8; });
               },
               "accessors[0]: the accessor's data does not fit its buffer view"});
  c.push_back({"stride_smaller_than_element",
               [](const fs::path& d) {
                 return quad(d, "stride.gltf",
                             [](Gltf& g) { g.doc["bufferViews"][0]["byteStride"] = 8; });
               },
               "accessors[0]: the view's byteStride is smaller than one element"});
  c.push_back({"sparse_overlapping",
               [](const fs::path& d) {
                 return quad(d, "sparse.gltf", [](Gltf& g) {
                   const std::vector<std::uint8_t> idx{2, 2};
                   const std::vector<float> values(6, 0.5f);
                   g.doc["accessors"][0]["sparse"] = {
                       {"count", 2},
                       {"indices", {{"bufferView", g.view(idx.data(), 2)}, {"componentType", kU8}}},
                       {"values", {{"bufferView", g.view(values.data(), 24)}}}};
                   g.doc["accessors"][0]["max"] = {1, 1, 0.5}; // bounds with the values
                 });
               },
               "accessors[0].sparse.indices: the sparse indices are not strictly increasing"});
  c.push_back({"accessor_index_out_of_range",
               [](const fs::path& d) {
                 return quad(d, "accidx.gltf", [](Gltf& g) {
                   g.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9;
                 });
               },
               "meshes[0].primitives[0].attributes.POSITION: index 9 refers to nothing"});
  c.push_back({"index_value_out_of_range",
               [](const fs::path& d) {
                 return quad(d, "index.gltf", [](Gltf& g) {
                   g.doc["meshes"][0]["primitives"][0]["indices"] =
                       g.indices(std::vector<std::uint16_t>{0, 1, 7});
                 });
               },
               "meshes[0].primitives[0].indices: an index is not less than the number of "
               "vertices"});
  c.push_back({"attribute_wrong_type",
               [](const fs::path& d) {
                 return quad(d, "type.gltf",
                             [](Gltf& g) { g.doc["accessors"][0]["type"] = "VEC4"; });
               },
               "meshes[0].primitives[0].attributes.POSITION: accessor format VEC4/5126 is not "
               "allowed for this attribute"});
  c.push_back({"attribute_wrong_component_type",
               [](const fs::path& d) {
                 return quad(d, "ctype.gltf",
                             [](Gltf& g) { g.doc["accessors"][0]["componentType"] = kU32; });
               },
               "meshes[0].primitives[0].attributes.POSITION: accessor format VEC3/5125 is not "
               "allowed for this attribute"});
  c.push_back({"indices_wrong_component_type",
               [](const fs::path& d) {
                 return quad(d, "ictype.gltf",
                             [](Gltf& g) { g.doc["accessors"][1]["componentType"] = kFloat; });
               },
               "meshes[0].primitives[0].indices: indices must be SCALAR unsigned byte, short or "
               "int"});
  // Nodes and indices.
  c.push_back({"node_cycle",
               [](const fs::path& d) {
                 return quad(d, "cycle.gltf", [](Gltf& g) {
                   // Below the scene's root (a cycle through a root also makes it a child).
                   g.doc["nodes"][0]["children"] = {1};
                   g.push("nodes", {{"children", {1}}});
                 });
               },
               "nodes[1]: the node is in a loop"});
  c.push_back(
      {"scene_out_of_range",
       [](const fs::path& d) { return quad(d, "scene.gltf", [](Gltf& g) { g.doc["scene"] = 3; }); },
       "scene: scene index 3 out of range (1 available)"});
  c.push_back({"mesh_out_of_range",
               [](const fs::path& d) {
                 return quad(d, "mesh.gltf", [](Gltf& g) { g.doc["nodes"][0]["mesh"] = 5; });
               },
               "nodes[0].mesh: index 5 refers to nothing"});
  c.push_back({"child_out_of_range",
               [](const fs::path& d) {
                 return quad(d, "child.gltf", [](Gltf& g) { g.doc["nodes"][0]["children"] = {9}; });
               },
               "nodes[0].children[0]: index 9 refers to nothing"});
  c.push_back({"material_out_of_range",
               [](const fs::path& d) {
                 return quad(d, "material.gltf",
                             [](Gltf& g) { g.doc["meshes"][0]["primitives"][0]["material"] = 4; });
               },
               "meshes[0].primitives[0].material: index 4 refers to nothing"});
  c.push_back({"negative_material",
               [](const fs::path& d) {
                 return quad(d, "negmat.gltf",
                             [](Gltf& g) { g.doc["meshes"][0]["primitives"][0]["material"] = -3; });
               },
               "meshes[0].primitives[0].material: an index must be a non-negative integer"});
  c.push_back({"index_beyond_int",
               [](const fs::path& d) {
                 return quad(d, "wrap.gltf",
                             [](Gltf& g) { g.doc["nodes"][0]["mesh"] = 4294967296u; });
               },
               "nodes[0].mesh: index 4294967296 refers to nothing"});
  c.push_back({"texture_out_of_range",
               [](const fs::path& d) {
                 return quad(d, "texture.gltf", [](Gltf& g) {
                   g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 3;
                 });
               },
               "materials[0].pbrMetallicRoughness.baseColorTexture.index: index 3 refers to "
               "nothing"});
  c.push_back({"yfov_zero",
               [](const fs::path& d) {
                 return quad(d, "yfov.gltf", [](Gltf& g) {
                   g.push("cameras", {{"type", "perspective"},
                                      {"perspective", {{"yfov", 0.0}, {"znear", 0.1}}}});
                   g.doc["nodes"][0]["camera"] = 0;
                 });
               },
               "cameras[0].perspective.yfov: value 0.0 is out of range"});
  c.push_back({"negative_emission",
               [](const fs::path& d) {
                 return quad(d, "emission.gltf", [](Gltf& g) {
                   g.doc["materials"][0]["emissiveFactor"] = {-1.0, 0.0, 0.0};
                 });
               },
               "materials[0].emissiveFactor[0]: value -1.0 is out of range"});
  c.push_back({"metallic_out_of_range",
               [](const fs::path& d) {
                 return quad(d, "metallic.gltf", [](Gltf& g) {
                   g.doc["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = 2.0;
                 });
               },
               "materials[0].pbrMetallicRoughness.metallicFactor: value 2.0 is out of range"});
  c.push_back({"no_triangles",
               [](const fs::path& d) {
                 return quad(d, "nomesh.gltf", [](Gltf& g) { g.doc["nodes"][0].erase("mesh"); });
               },
               "no triangles"});
  // Images.
  c.push_back({"image_not_png_or_jpeg",
               [](const fs::path& d) {
                 return textured_quad(d, "gif.gltf",
                                      {{"uri", "data:image/png;base64," +
                                                   base64({'G', 'I', 'F', '8', '9', 'a', 0, 0})}});
               },
               "images[0]: not a PNG, JPEG or WebP image"});
  c.push_back(
      {"image_does_not_decode",
       [](const fs::path& d) {
         std::vector<unsigned char> bytes = grey_png(4, 4);
         bytes.resize(bytes.size() - 20); // cut into the image data
         return textured_quad(d, "cut.gltf", {{"uri", "data:image/png;base64," + base64(bytes)}});
       },
       "images[0]: the PNG does not decode (corrupt data)"});
  c.push_back(
      {"image_empty_idat",
       [](const fs::path& d) {
         // Signature, IHDR (8 + 13 + 4 bytes), then an IDAT chunk of length 0.
         std::vector<unsigned char> bytes = grey_png(2, 2);
         const std::vector<unsigned char> empty{0,   0,   0,    0,    'I',  'D',
                                                'A', 'T', 0x35, 0xAF, 0x06, 0x1E};
         bytes.insert(bytes.begin() + 33, empty.begin(), empty.end());
         return textured_quad(d, "idat.gltf", {{"uri", "data:image/png;base64," + base64(bytes)}});
       },
       "images[0]: PNG with an empty IDAT chunk (not supported)"});
  c.push_back({"image_missing",
               [](const fs::path& d) {
                 return textured_quad(d, "noimg.gltf", {{"uri", "no.png"}});
               },
               "images[0]: external file 'no.png' not found"});
  c.push_back({"image_over_size_limit",
               [](const fs::path& d) {
                 return textured_quad(d, "large.gltf",
                                      {{"uri", "data:image/png;base64," + base64(grey_png(8, 2))}});
               },
               "images[0]: 8 x 2 texels exceed --max-texture-size 4",
               limits([](irad::LoadLimits& l) { l.max_texture_size = 4; }),
               "--max-texture-size 4"});
  c.push_back({"image_over_texel_limit",
               [](const fs::path& d) {
                 return textured_quad(d, "texels1.gltf",
                                      {{"uri", "data:image/png;base64," + base64(grey_png(8, 8))}});
               },
               "images[0]: 8 x 8 texels exceed the limit of 32 texels per image",
               limits([](irad::LoadLimits& l) { l.max_texture_texels = 32; }), ""});
  c.push_back({"images_over_texel_limit",
               [](const fs::path& d) {
                 // Two images of 25 texels each: each is under the limit, together they are over.
                 Gltf g = emissive_quad();
                 for (int k = 0; k < 2; ++k) {
                   g.push("images", {{"uri", "data:image/png;base64," + base64(grey_png(5, 5))}});
                   g.push("textures", {{"source", k}});
                 }
                 g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 0;
                 g.doc["materials"][0]["emissiveTexture"]["index"] = 1;
                 return g.write_gltf(d / "texels.gltf");
               },
               "images[1]: the images hold 50 texels, over the limit of 32 for all images "
               "together",
               limits([](irad::LoadLimits& l) { l.max_texture_texels = 32; }), ""});
  // Counts.
  c.push_back({"accessor_over_limit",
               [](const fs::path& d) { return quad(d, "count.gltf", [](Gltf&) {}); },
               "accessors[0]: count 4 is over the limit of 3 x 1 elements (--max-triangles)",
               limits([](irad::LoadLimits& l) { l.max_triangles = 1; }), "--max-triangles 1"});
  c.push_back({"triangles_over_limit",
               [](const fs::path& d) {
                 return quad(d, "triangles.gltf", [](Gltf& g) {
                   g.push("nodes", {{"mesh", 0}, {"translation", {0, 0, 1}}});
                   g.doc["scenes"][0]["nodes"] = {0, 1};
                 });
               },
               "meshes[0].primitives[0]: the scene would have 4 triangles, over the limit of 3 "
               "(--max-triangles)",
               limits([](irad::LoadLimits& l) { l.max_triangles = 3; }), "--max-triangles 3"});
  c.push_back({"vertices_over_limit",
               [](const fs::path& d) {
                 return quad(d, "vertices.gltf", [](Gltf& g) {
                   g.doc["meshes"][0]["primitives"][0]["indices"] =
                       g.indices(std::vector<std::uint16_t>{0, 1, 2});
                   g.push("nodes", {{"mesh", 0}, {"translation", {0, 0, 1}}});
                   g.doc["scenes"][0]["nodes"] = {0, 1};
                 });
               },
               "meshes[0].primitives[0]: the scene would have 8 vertices, over the limit of 3 x 2 "
               "(--max-triangles)",
               limits([](irad::LoadLimits& l) { l.max_triangles = 2; }), "--max-triangles 2"});
  return c;
}

class BadInput : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("irad_bad_input_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path dir_;
};

TEST_F(BadInput, EachCaseIsOneErrorNamingTheFileAndTheElement) {
  irad::Log log([](const std::string&) {});
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    fs::create_directories(dir_ / c.name);
    const fs::path path = c.make(dir_ / c.name);
    try {
      irad::load_gltf(path, log, c.limits);
      ADD_FAILURE() << "no error";
    } catch (const irad::Error& e) {
      EXPECT_EQ(std::string(e.what()), path.string() + ": " + c.message);
    }
  }
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST_F(BadInput, CommandLineExitsWithOneLineAndWritesNothing) {
  for (const Case& c : cases()) {
    if (c.limits.max_texture_texels != irad::LoadLimits{}.max_texture_texels) continue; // no flag
    SCOPED_TRACE(c.name);
    fs::create_directories(dir_ / c.name);
    const fs::path path = c.make(dir_ / c.name);
    const fs::path out = dir_ / c.name / "out.exr";
    const fs::path err = dir_ / c.name / "stderr.txt";
    const std::string cmd = std::string(IRAD_BINARY) + " render '" + path.string() + "' -o '" +
                            out.string() + "' --estimator rt-vpl --paths 4 --size 8x8 " +
                            c.cli_options + " > /dev/null 2> '" + err.string() + "'";
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 1);
    EXPECT_EQ(read_text(err), "irad: error: " + path.string() + ": " + c.message + "\n");
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(dir_ / c.name / "out.exr.tmp"));
  }
}

} // namespace
