// The semantic half of the glTF validator (core/gltf/validate_semantics*.cpp) against the
// Khronos glTF-Validator conformance files: no issue on any valid file, and on every invalid
// file whose report has an error in the semantic half's scope, at least one issue at (or
// above, or below) one of the report's error pointers.
#include "core/gltf/validate/validate_parts.h"
#include "tests/conformance_files.h"

#include <algorithm>
#include <cstdint>
#include <gtest/gtest.h>
#include <iostream>
#include <limits>
#include <set>
#include <string>
#include <vector>

namespace IRAD_UNITY_ID {

using irad::test::ConformanceFile;

// The error codes the semantic half reports (the schema half and the GLB/IO layer do the rest).
bool in_scope(const std::string& code) {
  static const std::set<std::string> exact = {
      "BUFFER_BYTE_LENGTH_MISMATCH", "BUFFER_MISSING_GLB_DATA",
      "INVALID_IBM_ACCESSOR_COUNT",  "ROTATION_NON_UNIT",
      "SCENE_NON_ROOT_NODE",         "IMAGE_BUFFER_VIEW_WITH_BYTESTRIDE",
      "IMAGE_DATA_INVALID",          "IMAGE_UNEXPECTED_EOS",
      "MESH_INVALID_WEIGHTS_COUNT",  "MESH_PRIMITIVES_UNEQUAL_TARGETS_COUNT"};
  if (exact.count(code) != 0) return true;
  for (const char* prefix :
       {"ACCESSOR_", "BUFFER_VIEW_", "MESH_PRIMITIVE_", "NODE_", "SKIN_", "ANIMATION_"})
    if (code.rfind(prefix, 0) == 0) return true;
  return false;
}

// Image data errors of images in external files: check_semantics sees only the buffers.
bool external_image(const ConformanceFile& f, const irad::test::ReportedError& e) {
  if (e.code.rfind("IMAGE_", 0) != 0 || e.code == "IMAGE_BUFFER_VIEW_WITH_BYTESTRIDE") return false;
  const auto image = f.root.value(nlohmann::json::json_pointer(e.pointer), nlohmann::json());
  return !image.is_object() || !image.contains("bufferView");
}

bool related(const std::string& a, const std::string& b) {
  const auto& shorter = a.size() < b.size() ? a : b;
  const auto& longer = a.size() < b.size() ? b : a;
  return longer.rfind(shorter, 0) == 0 &&
         (longer.size() == shorter.size() || longer[shorter.size()] == '/');
}

std::vector<irad::gltf::Issue> run(const ConformanceFile& f) {
  std::vector<irad::gltf::Issue> issues;
  irad::gltf::check_semantics(f.root, f.buffers, issues);
  return issues;
}

std::string rel(const ConformanceFile& f) {
  return std::filesystem::relative(f.path, irad::test::conformance_dir()).string();
}

TEST(GltfValidateSemantics, ConformanceFiles) {
  // ../shared is the project's, beside the checkout: a clone elsewhere has none (CI's has it).
  if (!std::filesystem::is_directory(irad::test::conformance_dir()))
    GTEST_SKIP() << "no conformance files at " << irad::test::conformance_dir();
  const auto documents = irad::test::conformance_documents();
  ASSERT_GT(documents.size(), 300u) << "conformance files not found";
  int valid = 0, valid_clean = 0, scoped = 0, caught = 0, skipped = 0;
  std::set<std::string> code_misses, extras;
  for (const auto& path : documents) {
    const auto file = irad::test::load_conformance_file(path);
    if (!file) {
      ++skipped;
      std::cout << "[semantics] skipped (unparsable): "
                << std::filesystem::relative(path, irad::test::conformance_dir()).string() << "\n";
      continue;
    }
    const auto issues = run(*file);
    if (file->errors.empty()) {
      ++valid;
      if (issues.empty()) ++valid_clean;
      for (const auto& i : issues)
        ADD_FAILURE() << rel(*file) << ": false alarm " << i.code << " at " << i.pointer << ": "
                      << i.message;
      continue;
    }
    // Diagnostics (printed, not asserted): reported errors without an issue of the same code
    // there, and issues of a code the report does not have there.
    for (const auto& e : file->errors) {
      if (!in_scope(e.code) || external_image(*file, e)) continue;
      bool same = false;
      for (const auto& i : issues)
        same = same || (i.code == e.code && related(i.pointer, e.pointer));
      if (!same) code_misses.insert(e.code + " (" + rel(*file) + ")");
    }
    for (const auto& i : issues) {
      bool same = false;
      for (const auto& e : file->errors)
        same = same || (i.code == e.code && related(i.pointer, e.pointer));
      if (!same) extras.insert(i.code + "@" + i.pointer + " (" + rel(*file) + ")");
    }
    std::vector<std::string> pointers;
    for (const auto& e : file->errors)
      if (in_scope(e.code) && !external_image(*file, e)) pointers.push_back(e.pointer);
    if (pointers.empty()) continue;
    ++scoped;
    bool hit = false;
    for (const auto& i : issues)
      for (const auto& p : pointers) hit = hit || related(i.pointer, p);
    if (hit) {
      ++caught;
      continue;
    }
    std::string want;
    for (const auto& e : file->errors)
      if (in_scope(e.code)) want += " " + e.code + "@" + e.pointer;
    ADD_FAILURE() << rel(*file) << ": missed" << want;
  }
  std::cout << "[semantics] valid files without issues: " << valid_clean << " / " << valid
            << "; invalid files in scope caught: " << caught << " / " << scoped << " (" << skipped
            << " files unparsable, skipped)\n";
  for (const auto& m : code_misses)
    std::cout << "[semantics] error not reported as such: " << m << "\n";
  for (const auto& x : extras) std::cout << "[semantics] issue not in the report: " << x << "\n";
}

// Replaces every object member and array element under `v` (down to `depth` levels) by each
// hostile value in turn, calling `run` after each replacement, and restores it.
template <class Run>
void mutate(nlohmann::json& v, int depth, const std::vector<nlohmann::json>& hostile, Run& run) {
  if (depth == 0 || !(v.is_object() || v.is_array())) return;
  std::vector<nlohmann::json*> children;
  if (v.is_object())
    for (auto& item : v.items()) children.push_back(&item.value());
  else
    for (std::size_t i = 0; i < std::min<std::size_t>(v.size(), 3); ++i) children.push_back(&v[i]);
  for (nlohmann::json* c : children) {
    const nlohmann::json saved = *c;
    for (const auto& h : hostile) {
      *c = h;
      run();
    }
    *c = saved;
    mutate(*c, depth - 1, hostile, run);
  }
}

// Every conformance file with each value of its first objects (to a few levels) replaced by
// hostile values, and with its buffers cut short: check_semantics must neither throw nor crash
// (built with the sanitizers, this also checks for undefined behaviour and stray reads).
TEST(GltfValidateSemantics, MutatedConformanceFilesNeverThrow) {
  // ../shared is the project's, beside the checkout: a clone elsewhere has none (CI's has it).
  if (!std::filesystem::is_directory(irad::test::conformance_dir()))
    GTEST_SKIP() << "no conformance files at " << irad::test::conformance_dir();
  const std::vector<nlohmann::json> hostile = {
      -1, 4294967295u, 1e30, 4611686018427387904, "x", nlohmann::json::array(), nullptr};
  std::size_t runs = 0;
  for (const auto& path : irad::test::conformance_documents()) {
    auto file = irad::test::load_conformance_file(path);
    if (!file || !file->root.is_object()) continue;
    std::vector<irad::gltf::Issue> issues;
    auto shorter = file->buffers;
    for (auto& b : shorter) b.size /= 2;
    EXPECT_NO_THROW(irad::gltf::check_semantics(file->root, shorter, issues)) << path;
    auto run = [&] {
      issues.clear();
      EXPECT_NO_THROW(irad::gltf::check_semantics(file->root, file->buffers, issues)) << path;
      ++runs;
    };
    for (auto& [key, list] : file->root.items())
      if (key != "asset" && key != "extensionsUsed") mutate(list, 5, hostile, run);
  }
  EXPECT_GT(runs, 10000u);
}

// Valid files using Draco and meshopt compression (none in the conformance set): their
// accessors' data is not in their views (Draco: no view; meshopt: a fallback buffer without
// data), so it must not be checked, and their layout raises nothing.
TEST(GltfValidateSemantics, CompressedDataIsNotChecked) {
  const auto root = nlohmann::json::parse(R"({
    "extensionsUsed": ["KHR_draco_mesh_compression", "EXT_meshopt_compression"],
    "buffers": [{"byteLength": 8}, {"byteLength": 48,
                 "extensions": {"EXT_meshopt_compression": {"fallback": true}}}],
    "bufferViews": [
      {"buffer": 0, "byteLength": 8},
      {"buffer": 1, "byteLength": 48, "byteStride": 12, "target": 34962,
       "extensions": {"EXT_meshopt_compression": {"buffer": 0, "byteLength": 8,
                      "byteStride": 12, "count": 4, "mode": "ATTRIBUTES"}}}],
    "accessors": [
      {"componentType": 5126, "type": "VEC3", "count": 4, "min": [0,0,0], "max": [1,1,1]},
      {"componentType": 5123, "type": "SCALAR", "count": 6},
      {"componentType": 5126, "type": "VEC3", "count": 4, "min": [0,0,0], "max": [1,1,1],
       "bufferView": 1}],
    "meshes": [{"primitives": [
      {"attributes": {"POSITION": 0}, "indices": 1,
       "extensions": {"KHR_draco_mesh_compression": {"bufferView": 0,
                      "attributes": {"POSITION": 0}}}},
      {"attributes": {"POSITION": 2}}]}]
  })");
  const unsigned char draco[8] = {'D', 'R', 'A', 'C', 'O', 2, 2, 1};
  // A loader may hand the fallback buffer over as zeros: still not the accessor's data.
  const std::vector<unsigned char> zeros(48, 0);
  const std::vector<irad::gltf::BufferBytes> buffers = {{draco, sizeof draco, true},
                                                        {zeros.data(), zeros.size(), true}};
  std::vector<irad::gltf::Issue> issues;
  irad::gltf::check_semantics(root, buffers, issues);
  for (const auto& i : issues) ADD_FAILURE() << i.code << " at " << i.pointer << ": " << i.message;
}

// The data checks read accessors a chunk at a time (16384 elements): a float VEC3 accessor of
// 40,000 elements, a NaN, a sparse substitution and a value over the declared max in its second
// and third chunks, and an index past the vertices in the index accessor's third chunk. Each is
// found once, the NaN by its component in the whole accessor.
TEST(GltfValidateSemantics, DataChecksSeeEveryChunk) {
  constexpr std::uint32_t kCount = 40000;
  std::vector<float> positions(3 * kCount);
  for (std::uint32_t e = 0; e < kCount; ++e) {
    positions[3 * e] = static_cast<float>(e % 100);
    positions[3 * e + 1] = static_cast<float>(e % 7);
    positions[3 * e + 2] = 0.5f;
  }
  positions[3 * 30000 + 1] = std::numeric_limits<float>::quiet_NaN(); // component 90001
  positions[3 * 35000] = 120.0f;                                      // over max 99
  std::vector<std::uint32_t> indices(39999);
  for (std::uint32_t k = 0; k < indices.size(); ++k) indices[k] = k;
  indices[39000] = kCount; // past the vertices
  const std::uint32_t sparse_index = 20000;
  const float sparse_value[3] = {-5.0f, 3.0f, 0.5f}; // under min 0
  std::vector<unsigned char> bytes;
  auto append = [&bytes](const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    bytes.insert(bytes.end(), b, b + n);
  };
  append(positions.data(), positions.size() * 4);
  append(indices.data(), indices.size() * 4);
  append(&sparse_index, 4);
  append(sparse_value, 12);
  nlohmann::json root = nlohmann::json::parse(R"({
    "buffers": [{"byteLength": 0}],
    "bufferViews": [{"buffer": 0, "byteLength": 480000, "target": 34962},
                    {"buffer": 0, "byteOffset": 480000, "byteLength": 159996, "target": 34963},
                    {"buffer": 0, "byteOffset": 639996, "byteLength": 4},
                    {"buffer": 0, "byteOffset": 640000, "byteLength": 12}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": 40000,
       "min": [0, 0, 0.5], "max": [99, 6, 0.5],
       "sparse": {"count": 1, "indices": {"bufferView": 2, "componentType": 5125},
                  "values": {"bufferView": 3}}},
      {"bufferView": 1, "componentType": 5125, "type": "SCALAR", "count": 39999}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}]
  })");
  root["buffers"][0]["byteLength"] = bytes.size();
  const std::vector<irad::gltf::BufferBytes> buffers = {{bytes.data(), bytes.size(), true}};
  std::vector<irad::gltf::Issue> issues;
  irad::gltf::check_semantics(root, buffers, issues);
  std::multiset<std::string> found;
  for (const auto& i : issues) {
    found.insert(i.code + " " + i.pointer + ": " + i.message);
    std::cout << i.code << " at " << i.pointer << ": " << i.message << "\n";
  }
  for (const char* want :
       {"ACCESSOR_INVALID_FLOAT /accessors/0: component 90001 is NaN or infinite",
        "ACCESSOR_MIN_MISMATCH /accessors/0/min/0: declared min 0 but the data's is -5",
        "ACCESSOR_ELEMENT_OUT_OF_MIN_BOUND /accessors/0/min/0: 1 element(s) lie outside the "
        "declared min",
        "ACCESSOR_MAX_MISMATCH /accessors/0/max/0: declared max 99 but the data's is 120",
        "ACCESSOR_ELEMENT_OUT_OF_MAX_BOUND /accessors/0/max/0: 1 element(s) lie outside the "
        "declared max"})
    EXPECT_EQ(found.count(want), 1u) << want;
  EXPECT_EQ(std::count_if(issues.begin(), issues.end(),
                          [](const auto& i) { return i.code == "ACCESSOR_INDEX_OOB"; }),
            1);
  // Nothing else about accessor 0's components 1 and 2: the NaN is skipped in the bounds.
  for (const auto& i : issues)
    if (i.pointer.rfind("/accessors/0/m", 0) == 0) {
      EXPECT_EQ(i.pointer.back(), '0') << i.code << " at " << i.pointer;
    }
}

// Any JSON value in any place: the checks read defensively and never throw.
TEST(GltfValidateSemantics, HostileJsonNeverThrows) {
  const char* docs[] = {
      R"({"accessors":[{"bufferView":"x","count":-5,"componentType":5126,"type":"VEC3",
         "min":[1,"a"],"sparse":{"count":1e30,"indices":7}}],"bufferViews":[1,null]})",
      R"({"meshes":[{"primitives":[{"attributes":{"POSITION":99,"TEXCOORD_0":-1},
         "targets":[{"POSITION":1e300},[]],"material":{"a":1}}],"weights":"w"}],
         "materials":[{"normalTexture":{"index":0,"texCoord":1e99}}]})",
      R"({"nodes":[{"children":[0,0,1e20,-1]},{"children":"c","matrix":[1,2]}],
         "scenes":[{"nodes":[0,1,5]}],"skins":[{"joints":[0,1,7],"skeleton":3,
         "inverseBindMatrices":0}],"accessors":[{"count":1,"componentType":5126,"type":"MAT4",
         "bufferView":0}],"bufferViews":[{"buffer":0,"byteLength":64}],"buffers":[{"byteLength":64}]})",
      R"({"animations":[{"samplers":[{"input":0,"output":0,"interpolation":5}],
         "channels":[{"sampler":0,"target":{"node":0,"path":"weights"}},{"target":3}]}],
         "nodes":[{"mesh":0,"matrix":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1]}],"meshes":[[]],
         "accessors":[{"count":4,"componentType":5126,"type":"SCALAR","bufferView":0,
         "byteOffset":1}],"bufferViews":[{"buffer":0,"byteLength":16,"byteStride":4}],
         "buffers":[{"byteLength":16}],"images":[{"bufferView":0}]})",
      R"([1,2,3])",
      R"("text")",
      R"(null)"};
  const unsigned char bytes[8] = {0x89, 'P', 'N', 'G', 0, 0, 0, 0};
  const std::vector<irad::gltf::BufferBytes> buffers = {{bytes, sizeof bytes, true}};
  for (const char* doc : docs) {
    const auto root = nlohmann::json::parse(doc);
    std::vector<irad::gltf::Issue> issues;
    EXPECT_NO_THROW(irad::gltf::check_semantics(root, buffers, issues)) << doc;
    EXPECT_NO_THROW(irad::gltf::check_semantics(root, {}, issues)) << doc;
  }
}

} // namespace IRAD_UNITY_ID
