// check_schema (core/gltf/validate_schema*.cpp) against the Khronos glTF-Validator's
// conformance files: each NAME.gltf / NAME.glb beside NAME.report.json. Valid files (no errors)
// must give no issue; an invalid file whose report has an error with a code check_schema covers
// must give an issue at (or above / below) one of those errors' JSON pointers.
#include "core/gltf/validate/validate_parts.h"
#include "tests/test_paths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace IRAD_UNITY_ID {

namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kConformance =
    fs::path(IRAD_SOURCE_DIR) / "../shared/conformance/gltf-validator/test";

// The codes check_schema reports (the JSON-only errors of the validator).
const std::set<std::string> kScope{"UNDEFINED_PROPERTY",
                                   "INVALID_INDEX",
                                   "TYPE_MISMATCH",
                                   "ARRAY_TYPE_MISMATCH",
                                   "VALUE_NOT_IN_RANGE",
                                   "EMPTY_ENTITY",
                                   "UNRESOLVED_REFERENCE",
                                   "ARRAY_LENGTH_NOT_IN_LIST",
                                   "ONE_OF_MISMATCH",
                                   "PATTERN_MISMATCH",
                                   "VALUE_MULTIPLE_OF",
                                   "UNSATISFIED_DEPENDENCY",
                                   "DUPLICATE_ELEMENTS",
                                   "UNDECLARED_EXTENSION",
                                   "UNEXPECTED_EXTENSION_OBJECT",
                                   "NON_REQUIRED_EXTENSION",
                                   "UNUSED_EXTENSION_REQUIRED",
                                   "INVALID_URI",
                                   "BUFFER_DATA_URI_MIME_TYPE_INVALID",
                                   "IMAGE_MIME_TYPE_INVALID",
                                   "TEXTURE_INVALID_IMAGE_MIME_TYPE",
                                   "IMAGE_NON_ENABLED_MIME_TYPE",
                                   "UNKNOWN_ASSET_MAJOR_VERSION",
                                   "ASSET_MIN_VERSION_GREATER_THAN_VERSION",
                                   "CAMERA_ZFAR_LEQUAL_ZNEAR",
                                   "CAMERA_XMAG_YMAG_ZERO",
                                   "KHR_LIGHTS_PUNCTUAL_LIGHT_SPOT_ANGLES",
                                   "KHR_MATERIALS_VARIANTS_NON_UNIQUE_VARIANT",
                                   "KHR_ANIMATION_POINTER_ANIMATION_CHANNEL_TARGET_NODE",
                                   "KHR_ANIMATION_POINTER_ANIMATION_CHANNEL_TARGET_PATH"};

std::string read_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::uint32_t u32(const std::string& s, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, s.data() + at, sizeof v);
  return v; // GLB is little-endian, as are the machines irad runs on
}

// The document's JSON; nullopt when it has none that parses.
std::optional<json> load_document(const fs::path& p) {
  std::string text = read_file(p);
  if (p.extension() == ".glb") {
    if (text.size() < 20 || u32(text, 16) != 0x4E4F534Au) return std::nullopt;
    const std::size_t length = u32(text, 12);
    if (length > text.size() - 20) return std::nullopt;
    text = text.substr(20, length);
  }
  json doc = json::parse(text, nullptr, false);
  if (doc.is_discarded()) return std::nullopt;
  return doc;
}

// Pointers related as equal or as ancestor and descendant.
bool related(const std::string& a, const std::string& b) {
  const auto under = [](const std::string& top, const std::string& p) {
    return p.starts_with(top) &&
           (top.empty() || top == "/" || p.size() == top.size() || p[top.size()] == '/');
  };
  return under(a, b) || under(b, a);
}

struct Conformance {
  int valid = 0, valid_clean = 0, in_scope = 0, caught = 0;
  int errors = 0, exact = 0; // in-scope errors, and those matched by code and pointer
  std::vector<std::string> false_alarms, misses, inexact, extra;
};

void check_file(const fs::path& doc_path, const json& report, Conformance& c) {
  const std::optional<json> doc = load_document(doc_path);
  if (!doc) return;
  std::vector<irad::gltf::Issue> issues;
  irad::gltf::check_schema(*doc, issues);
  const std::string name = fs::relative(doc_path, kConformance).string();
  if (report["issues"]["numErrors"] == 0) {
    ++c.valid;
    if (issues.empty())
      ++c.valid_clean;
    else
      c.false_alarms.push_back(name + ": " + issues[0].code + " at " + issues[0].pointer);
    return;
  }
  // Issues the report does not have as errors (false alarms on an invalid file).
  for (const auto& issue : issues) {
    const bool reported = std::any_of(report["issues"]["messages"].begin(),
                                      report["issues"]["messages"].end(), [&](const json& m) {
                                        return m["severity"] == 0 && m["code"] == issue.code &&
                                               m.value("pointer", "") == issue.pointer;
                                      });
    if (!reported) c.extra.push_back(name + ": " + issue.code + " at " + issue.pointer);
  }
  std::vector<std::string> expected;
  for (const json& m : report["issues"]["messages"]) {
    if (m["severity"] != 0 || kScope.count(m["code"].get<std::string>()) == 0) continue;
    expected.push_back(m.value("pointer", ""));
    ++c.errors;
    const bool found = std::any_of(issues.begin(), issues.end(), [&](const auto& i) {
      return i.code == m["code"] && i.pointer == expected.back();
    });
    if (found)
      ++c.exact;
    else
      c.inexact.push_back(name + ": " + m["code"].get<std::string>() + " at " + expected.back());
  }
  if (expected.empty()) return;
  ++c.in_scope;
  for (const auto& issue : issues)
    for (const auto& p : expected)
      if (related(issue.pointer, p)) {
        ++c.caught;
        return;
      }
  c.misses.push_back(name + " (expected " + expected[0] + ")");
}

TEST(GltfValidateSchema, ConformanceFiles) {
  // ../shared is the project's, beside the checkout: a clone elsewhere has none (CI's has it).
  if (!fs::is_directory(kConformance)) GTEST_SKIP() << "no conformance files at " << kConformance;
  Conformance c;
  for (const auto& entry : fs::recursive_directory_iterator(kConformance)) {
    const fs::path& p = entry.path();
    if (p.extension() != ".gltf" && p.extension() != ".glb") continue;
    const fs::path report_path = p.string() + ".report.json";
    if (!fs::exists(report_path)) continue;
    const json report = json::parse(read_file(report_path), nullptr, false);
    if (!report.is_object()) continue;
    check_file(p, report, c);
  }
  std::printf("check_schema: valid files without issues %d / %d; invalid files in scope caught "
              "%d / %d\n",
              c.valid_clean, c.valid, c.caught, c.in_scope);
  for (const auto& f : c.false_alarms) std::printf("  false alarm: %s\n", f.c_str());
  for (const auto& m : c.misses) std::printf("  missed: %s\n", m.c_str());
  std::printf("check_schema: in-scope errors matched by code and pointer %d / %d\n", c.exact,
              c.errors);
  for (const auto& m : c.inexact) std::printf("  not matched exactly: %s\n", m.c_str());
  std::printf("check_schema: issues on invalid files that their reports lack as errors: %zu\n",
              c.extra.size());
  for (const auto& m : c.extra) std::printf("  not in the report: %s\n", m.c_str());
  EXPECT_GT(c.valid, 100);
  EXPECT_TRUE(c.false_alarms.empty());
  EXPECT_GT(c.in_scope, 100);
  EXPECT_TRUE(c.misses.empty());
  EXPECT_TRUE(c.extra.empty());
}

// Every value of a document replaced by values of every JSON type (and non-finite numbers):
// check_schema must not throw.
TEST(GltfValidateSchema, NeverThrowsOnMutatedDocuments) {
  // ../shared is the project's, beside the checkout: a clone elsewhere has none (CI's has it).
  if (!fs::is_directory(kConformance)) GTEST_SKIP() << "no conformance files at " << kConformance;
  const std::array<json, 9> odd{json(nullptr),
                                json(std::numeric_limits<double>::quiet_NaN()),
                                json(-1),
                                json(1.5),
                                json("x"),
                                json::array(),
                                json::object(),
                                json(std::numeric_limits<double>::infinity()),
                                json::array({-1, "x", nullptr})};
  int documents = 0;
  for (const auto& entry : fs::recursive_directory_iterator(kConformance)) {
    const fs::path& file = entry.path();
    if (file.extension() != ".gltf" || entry.file_size() > 4096) continue;
    const std::optional<json> doc = load_document(file);
    if (!doc || !doc->is_object()) continue;
    const json flat = doc->flatten();
    std::set<std::string> pointers;
    for (auto it = flat.begin(); it != flat.end(); ++it) {
      // Every leaf and every ancestor of it.
      std::string p = it.key();
      while (!p.empty()) {
        pointers.insert(p);
        p = p.substr(0, p.rfind('/'));
      }
    }
    // Two odd values per element, in turn, keep the test fast; across the files every element
    // kind meets every value.
    std::size_t turn = 0;
    for (const auto& p : pointers)
      for (int k = 0; k < 2; ++k) {
        const json& v = odd[turn++ % odd.size()];
        json mutated = *doc;
        mutated[json::json_pointer(p)] = v;
        std::vector<irad::gltf::Issue> issues;
        EXPECT_NO_THROW(irad::gltf::check_schema(mutated, issues)) << file << " " << p;
        ++documents;
      }
  }
  EXPECT_GT(documents, 100);
}

TEST(GltfValidateSchema, NonObjectDocuments) {
  for (const json& v : {json(nullptr), json(1), json::array(), json("gltf")}) {
    std::vector<irad::gltf::Issue> issues;
    irad::gltf::check_schema(v, issues);
    ASSERT_EQ(issues.size(), 1u);
    EXPECT_EQ(issues[0].code, "TYPE_MISMATCH");
  }
}

} // namespace IRAD_UNITY_ID

namespace IRAD_UNITY_ID {

// The issues of a document given as JSON text, as "CODE pointer" lines.
std::vector<std::string> issues_of(const char* text) {
  std::vector<irad::gltf::Issue> issues;
  irad::gltf::check_schema(json::parse(text), issues);
  std::vector<std::string> out;
  for (const auto& i : issues) out.push_back(i.code + " " + i.pointer);
  return out;
}

using Lines = std::vector<std::string>;

TEST(GltfValidateSchema, IndicesAndIntegers) {
  // Whole numbers written as floats are integers; negative or fractional indices are not.
  EXPECT_EQ(issues_of(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":4.0}],
                          "bufferViews":[{"buffer":0.0,"byteLength":4}]})"),
            Lines{});
  EXPECT_EQ(
      issues_of(R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":4}],
                          "bufferViews":[{"buffer":-1,"byteLength":4,"byteStride":6},
                                         {"buffer":0.5,"byteLength":4}]})"),
      (Lines{"INVALID_INDEX /bufferViews/0/buffer", "VALUE_MULTIPLE_OF /bufferViews/0/byteStride",
             "TYPE_MISMATCH /bufferViews/1/buffer"}));
  EXPECT_EQ(issues_of(R"({"asset":{"version":"2.0"},"nodes":[{"children":[0,-1,"a",0]}]})"),
            (Lines{"INVALID_INDEX /nodes/0/children/1", "INVALID_INDEX /nodes/0/children/2",
                   "DUPLICATE_ELEMENTS /nodes/0/children/3"}));
}

TEST(GltfValidateSchema, Extensions) {
  // A known extension outside extensionsUsed is only undeclared; declared and misplaced, it is
  // unexpected; an unknown declared one is accepted.
  EXPECT_EQ(issues_of(R"({"asset":{"version":"2.0"},"samplers":[{"extensions":{
                          "KHR_materials_unlit":{}}}]})"),
            Lines{"UNDECLARED_EXTENSION /samplers/0/extensions/KHR_materials_unlit"});
  EXPECT_EQ(issues_of(R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_materials_unlit",
                          "EXT_whatever"],"samplers":[{"extensions":{"KHR_materials_unlit":{},
                          "EXT_whatever":{}}}]})"),
            Lines{"UNEXPECTED_EXTENSION_OBJECT /samplers/0/extensions/KHR_materials_unlit"});
}

TEST(GltfValidateSchema, HugeArraysStayFast) {
  // 100000 node indices, 0 and 1 alternating: uniqueness must not be quadratic.
  json doc = json::parse(R"({"asset":{"version":"2.0"},"nodes":[{}]})");
  json children = json::array();
  for (int i = 0; i < 100000; ++i) children.push_back(i % 2);
  doc["scenes"] = json::array({json{{"nodes", children}}});
  std::vector<irad::gltf::Issue> issues;
  irad::gltf::check_schema(doc, issues);
  // Every 1 is unresolved; every element but the first two repeats an earlier one.
  EXPECT_EQ(issues.size(), 50000u + 99998u);
}

} // namespace IRAD_UNITY_ID
