// The Khronos glTF-Validator's conformance files (../shared/conformance/gltf-validator/test/**,
// each NAME.gltf or NAME.glb beside NAME.report.json) through irad::load_gltf. Each file gets one
// emissive triangle (conformance_probe.h) so that it reaches its defect instead of stopping at
// "no triangles" or "no light"; the probe leaves broken files as they are. Contracts:
//  (a) every valid file (numErrors 0) loads, except the few listed in kAllowed with their reason
//      (checked against the file's content: the list is exactly the valid files showing one);
//  (b) every invalid file is refused (irad::Error) or warned (at least one warning);
//  (c) every message is irad's: one line, starting with the file's path and ": ", nothing of
//      tinygltf's text.
// A summary line gives the counts, and how many messages name one of the report's error
// pointers (printed, not asserted). Load only, no rendering.
#include "conformance_probe.h"
#include "core/gltf/loader.h"
#include "core/util/error.h"
#include "core/util/log.h"
#include "tests/test_paths.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <gtest/gtest.h>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using nlohmann::json;

namespace IRAD_UNITY_ID {

const fs::path kSuite = fs::path(IRAD_SOURCE_DIR) / "../shared/conformance/gltf-validator/test";

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The glTF JSON of a .gltf or .glb (null when it cannot be read as such).
json document_of(const fs::path& p) {
  std::string bytes = read_bytes(p);
  if (p.extension() == ".glb") {
    if (bytes.size() < 20) return nullptr;
    std::uint32_t n = 0;
    for (int i = 3; i >= 0; --i) n = (n << 8) | static_cast<unsigned char>(bytes[12 + i]);
    bytes = bytes.substr(20, n);
  }
  return json::parse(bytes, nullptr, false);
}

// The reasons a valid file may be refused; each is a predicate on the document and its folder.
using Reason = std::function<bool(const json&, const fs::path&)>;

bool any_of(const json& doc, const char* array, const std::function<bool(const json&)>& pred) {
  if (!doc.is_object() || !doc.contains(array) || !doc[array].is_array()) return false;
  return std::any_of(doc[array].begin(), doc[array].end(), pred);
}

bool min_version_beyond_2_0(const json& doc, const fs::path&) {
  return doc.is_object() && doc.contains("asset") && doc["asset"].is_object() &&
         doc["asset"].value("minVersion", "2.0") != "2.0";
}

bool yfov_at_least_pi(const json& doc, const fs::path&) {
  return any_of(doc, "cameras", [](const json& c) {
    const json p = c.is_object() ? c.value("perspective", json()) : json();
    return p.is_object() && p.value("yfov", 0.0) >= std::numbers::pi;
  });
}

bool known_image_bytes(const std::string& b) {
  return b.rfind("\x89PNG\r\n\x1a\n", 0) == 0 || b.rfind("\xFF\xD8\xFF", 0) == 0 ||
         (b.size() >= 12 && b.compare(0, 4, "RIFF") == 0 && b.compare(8, 4, "WEBP") == 0);
}

bool unknown_image_format(const json& doc, const fs::path& folder) {
  return any_of(doc, "images", [&](const json& image) {
    const std::string uri = image.is_object() ? image.value("uri", "") : "";
    if (uri.empty() || uri.rfind("data:", 0) == 0) return false;
    return fs::is_regular_file(folder / uri) && !known_image_bytes(read_bytes(folder / uri));
  });
}

bool unknown_accessor_type(const json& doc, const fs::path&) {
  static const std::vector<std::string> kTypes = {"SCALAR", "VEC2", "VEC3", "VEC4",
                                                  "MAT2",   "MAT3", "MAT4"};
  return any_of(doc, "accessors", [](const json& a) {
    const std::string type = a.is_object() ? a.value("type", "SCALAR") : "SCALAR";
    return std::find(kTypes.begin(), kTypes.end(), type) == kTypes.end();
  });
}

bool http_uri(const json& doc, const fs::path&) {
  const auto remote = [](const json& e) {
    const std::string uri = e.is_object() ? e.value("uri", "") : "";
    return uri.rfind("http://", 0) == 0 || uri.rfind("https://", 0) == 0;
  };
  return any_of(doc, "buffers", remote) || any_of(doc, "images", remote);
}

struct Allowed {
  const char* reason;
  Reason shows;
};

// Valid files that irad may refuse, by path under the suite, with the reason.
const std::map<std::string, Allowed>& allowed() {
  static const std::map<std::string, Allowed> kAllowed = {
      {"base/data/asset/min_version_valid.gltf",
       {"asset.minVersion 2.1: a glTF 2.1 feature irad does not know", &min_version_beyond_2_0}},
      {"base/data/camera/perspective_yfov.gltf",
       {"yfov >= pi: no perspective projection", &yfov_at_least_pi}},
      {"base/data/image/unrecognized_format.gltf",
       {"an image that is neither PNG, JPEG nor WebP", &unknown_image_format}},
      {"base/data/accessor/unknown_type.gltf",
       {"an accessor type that does not exist", &unknown_accessor_type}},
      {"base/data/buffer/non_relative_uri.gltf",
       {"an http(s) URI: irad reads no network", &http_uri}},
  };
  return kAllowed;
}

// One JSON pointer token with ~1 and ~0 unescaped.
std::string unescape_token(const std::string& token) {
  std::string out;
  for (std::size_t i = 0; i < token.size(); ++i) {
    if (token[i] == '~' && i + 1 < token.size() && (token[i + 1] == '0' || token[i + 1] == '1')) {
      out += token[++i] == '1' ? '/' : '~';
    } else {
      out += token[i];
    }
  }
  return out;
}

// "/a/3/b" -> "a[3].b" (JSON pointer to irad's element form).
std::string element_of(const std::string& pointer) {
  std::string out;
  for (std::size_t at = 1; at <= pointer.size() && !pointer.empty();) {
    const std::size_t end = std::min(pointer.find('/', at), pointer.size());
    const std::string token = unescape_token(pointer.substr(at, end - at));
    const bool index = !token.empty() && token.find_first_not_of("0123456789") == std::string::npos;
    out += index ? "[" + token + "]" : (out.empty() ? "" : ".") + token;
    at = end + 1;
  }
  return out;
}

enum class Kind { refused, warned, clean };

struct Case {
  std::string name; // path under the suite
  fs::path copy;    // the (probed) copy that is loaded
  bool valid = false;
  bool probed = false;
  std::vector<std::string> error_pointers; // of the report's errors (severity 0), non-empty ones
  Kind kind = Kind::clean;
  bool irad_error = true;            // false: something other than irad::Error was thrown
  std::vector<std::string> messages; // what() of the error, then the warnings
};

void load(Case& c) {
  std::vector<std::string> warnings;
  irad::Log log([&](const std::string& line) {
    const std::string prefix = "warning: ";
    if (line.rfind(prefix, 0) == 0) warnings.push_back(line.substr(prefix.size()));
  });
  try {
    (void)irad::load_gltf(c.copy, log);
    c.kind = warnings.empty() ? Kind::clean : Kind::warned;
  } catch (const irad::Error& e) {
    c.kind = Kind::refused;
    c.messages.push_back(e.what());
  } catch (const std::exception& e) {
    c.kind = Kind::refused;
    c.irad_error = false;
    c.messages.push_back(e.what());
  }
  c.messages.insert(c.messages.end(), warnings.begin(), warnings.end());
}

// The folder of the probed copies: $IRAD_CONFORMANCE_OUT, kept (tests/conformance_probe_check.js
// validates it), else a temporary one of this process (ctest runs each test in its own process,
// several at once), removed once loaded.
fs::path copies_folder() {
  const char* out = std::getenv("IRAD_CONFORMANCE_OUT");
  if (out != nullptr && *out != '\0') return out;
  return fs::path(::testing::TempDir()) / ("irad_conformance_" + std::to_string(::getpid()));
}

// Copies the suite into a folder once (relative URIs keep working), probes each file in place
// there and loads it.
std::vector<Case> run_suite() {
  const fs::path dir = copies_folder();
  fs::remove_all(dir);
  fs::copy(kSuite, dir, fs::copy_options::recursive);
  std::vector<Case> cases;
  for (const auto& entry : fs::recursive_directory_iterator(kSuite)) {
    const std::string report_name = entry.path().filename().string();
    const std::string suffix = ".report.json";
    if (report_name.size() <= suffix.size() || !report_name.ends_with(suffix)) continue;
    const fs::path source =
        entry.path().parent_path() / report_name.substr(0, report_name.size() - suffix.size());
    if (!fs::is_regular_file(source)) continue;
    Case c;
    c.name = fs::relative(source, kSuite).generic_string();
    c.copy = dir / c.name;
    const json report = json::parse(read_bytes(entry.path()));
    c.valid = report["issues"]["numErrors"] == 0;
    for (const json& m : report["issues"]["messages"]) {
      if (m.value("severity", 1) == 0 && !m.value("pointer", "").empty()) {
        c.error_pointers.push_back(m["pointer"]);
      }
    }
    const std::string bytes = read_bytes(source);
    const auto probe = source.extension() == ".glb" ? irad::test::probe_glb(bytes)
                                                    : irad::test::probe_gltf_json(bytes);
    if (probe) std::ofstream(c.copy, std::ios::binary | std::ios::trunc) << *probe;
    c.probed = probe.has_value();
    load(c);
    cases.push_back(std::move(c));
  }
  if (std::getenv("IRAD_CONFORMANCE_OUT") == nullptr) fs::remove_all(dir);
  std::sort(cases.begin(), cases.end(),
            [](const Case& a, const Case& b) { return a.name < b.name; });
  return cases;
}

// Computed once for the tests below, then only read.
const std::vector<Case>& suite() {
  static const std::vector<Case> kCases = run_suite();
  return kCases;
}

bool names_pointer(const std::string& message, const std::vector<std::string>& pointers) {
  return std::any_of(pointers.begin(), pointers.end(), [&](const std::string& p) {
    return message.find(p) != std::string::npos || message.find(element_of(p)) != std::string::npos;
  });
}

// Text of tinygltf's: its name, its phrases, or its lines joined by the loader with "; " (a
// sentence, capitalised or ended by a period, after the join; irad's own "; " clauses are
// lower-case).
bool looks_like_tinygltf(const std::string& m) {
  std::string lower = m;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  if (lower.find("tinygltf") != std::string::npos) return true;
  for (const char* phrase : {"property is missing", "Failed to", "File not found", ".; "}) {
    if (m.find(phrase) != std::string::npos) return true;
  }
  for (std::size_t i = m.find("; "); i != std::string::npos; i = m.find("; ", i + 1)) {
    if (i + 2 < m.size() && std::isupper(static_cast<unsigned char>(m[i + 2]))) return true;
  }
  return false;
}

// The refusal of a file without geometry or light (unprobed files): not a verdict on the defect.
bool stops_before_the_defect(const std::string& message) {
  return message.ends_with(": no triangles") || message.find(": no light: ") != std::string::npos;
}

class Conformance : public ::testing::Test {
protected:
  void SetUp() override {
    if (!fs::is_directory(kSuite)) GTEST_SKIP() << "no conformance files at " << kSuite;
  }
};

TEST_F(Conformance, AllowedListIsExactlyTheValidFilesShowingAReason) {
  std::map<std::string, bool> listed;
  for (const auto& [name, a] : allowed()) listed[name] = false;
  for (const Case& c : suite()) {
    if (!c.valid) continue;
    const json doc = document_of(kSuite / c.name);
    const fs::path folder = (kSuite / c.name).parent_path();
    for (const auto& [name, a] : allowed()) {
      if (a.shows(doc, folder) && name != c.name) {
        ADD_FAILURE() << c.name << " shows '" << a.reason << "' but is not in the allowed list";
      }
    }
    if (const auto it = allowed().find(c.name); it != allowed().end()) {
      listed[c.name] = true;
      EXPECT_TRUE(it->second.shows(doc, folder)) << c.name << ": " << it->second.reason;
    }
  }
  for (const auto& [name, seen] : listed) EXPECT_TRUE(seen) << name << " is not a valid file";
}

TEST_F(Conformance, ValidFilesLoad) {
  for (const Case& c : suite()) {
    if (!c.valid || allowed().count(c.name)) continue;
    if (c.kind == Kind::refused)
      ADD_FAILURE() << "valid file refused: " << c.name << (c.probed ? "" : " (no probe)") << ": "
                    << (c.messages.empty() ? "" : c.messages.front());
  }
}

TEST_F(Conformance, InvalidFilesAreRefusedOrWarned) {
  for (const Case& c : suite()) {
    if (c.valid) continue;
    if (c.kind == Kind::clean)
      ADD_FAILURE() << c.name << (c.probed ? "" : " (no probe)")
                    << " loads silently; the report's first error: "
                    << (c.error_pointers.empty() ? "" : c.error_pointers.front());
  }
}

TEST_F(Conformance, MessagesAreIrads) {
  for (const Case& c : suite()) {
    EXPECT_TRUE(c.irad_error) << c.name << ": not an irad::Error: " << c.messages.front();
    const std::string prefix = c.copy.string() + ": ";
    for (const std::string& m : c.messages) {
      EXPECT_EQ(m.rfind(prefix, 0), 0u) << c.name << ": does not start with the path: " << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << c.name << ": more than one line: " << m;
      EXPECT_FALSE(looks_like_tinygltf(m)) << c.name << ": tinygltf's text: " << m;
    }
  }
}

TEST_F(Conformance, Summary) {
  int valid = 0, loaded = 0, refused = 0, warned = 0, probed = 0;
  int messages = 0, naming = 0, files_naming = 0, no_geometry = 0;
  std::vector<std::string> silent;
  for (const Case& c : suite()) {
    probed += c.probed;
    if (c.valid) {
      ++valid;
      loaded += c.kind != Kind::refused;
      continue;
    }
    if (c.kind == Kind::clean) {
      silent.push_back(c.name);
      continue;
    }
    (c.kind == Kind::refused ? refused : warned) += 1;
    if (c.kind == Kind::refused && stops_before_the_defect(c.messages.front())) ++no_geometry;
    bool named = false;
    for (const std::string& m : c.messages) {
      ++messages;
      naming += names_pointer(m, c.error_pointers);
      named = named || names_pointer(m, c.error_pointers);
    }
    files_naming += named;
  }
  const int invalid = static_cast<int>(suite().size()) - valid;
  std::ostringstream line;
  line << "conformance: valid loaded " << loaded << "/" << valid << "; invalid " << invalid
       << ": refused " << refused << " (" << no_geometry
       << " of them by 'no triangles' or 'no light'), warned " << warned << ", silent "
       << silent.size() << "; probed " << probed << "/" << suite().size()
       << "; messages of refused/warned "
       << "invalid files naming a report error pointer: " << naming << "/" << messages << " (in "
       << files_naming << "/" << refused + warned << " files)";
  std::cout << line.str() << "\n";
  for (const std::string& name : silent) std::cout << "  silent: " << name << "\n";
  EXPECT_EQ(suite().size(), 372u) << "the suite holds 129 valid and 243 invalid files";
}

} // namespace
