#include "core/gltf/issue_book.h"

#include "core/gltf/read/json_read.h"
#include "core/util/error.h"

#include <algorithm>
#include <array>
#include <string_view>
#include <utility>

namespace irad::gltf {

namespace {

// Problems the loader repairs where it uses them, with the repair it makes.
struct Repair {
  const char* code;
  const char* what;
};
constexpr std::array<Repair, 13> kRepairs{{
    {"MESH_PRIMITIVE_TOO_FEW_TEXCOORDS", "the missing texture coordinates read as (0, 0)"},
    {"ACCESSOR_ELEMENT_OUT_OF_MAX_BOUND", "irad computes the bounds itself"},
    {"ACCESSOR_ELEMENT_OUT_OF_MIN_BOUND", "irad computes the bounds itself"},
    {"ACCESSOR_WEIGHTS_NON_NORMALIZED", "the weights are renormalised to sum 1"},
    {"ACCESSOR_INVALID_FLOAT",
     "triangles with a NaN or Inf vertex are dropped, such normals replaced"},
    {"ROTATION_NON_UNIT", "the quaternion is normalised"},
    {"ACCESSOR_ANIMATION_SAMPLER_OUTPUT_NON_NORMALIZED_QUATERNION",
     "the quaternions are normalised"},
    {"ACCESSOR_VECTOR3_NON_UNIT", "the normals are normalised"},
    {"MESH_PRIMITIVE_POSITION_ACCESSOR_WITHOUT_BOUNDS", "irad computes the bounds itself"},
    {"ACCESSOR_MIN_MISMATCH", "irad computes the bounds itself"},
    {"ACCESSOR_MAX_MISMATCH", "irad computes the bounds itself"},
    {"ANIMATION_SAMPLER_INPUT_ACCESSOR_WITHOUT_BOUNDS", "irad reads the times themselves"},
    {"ACCESSOR_NON_CLAMPED", "the values are clamped"},
}};

bool at_or_below(const std::string& pointer, const std::string& prefix) {
  return pointer.size() >= prefix.size() && pointer.compare(0, prefix.size(), prefix) == 0 &&
         (pointer.size() == prefix.size() || pointer[prefix.size()] == '/' || prefix.empty());
}

} // namespace

const char* repair_of(const std::string& code) {
  for (const Repair& r : kRepairs)
    if (code == r.code) return r.what;
  return nullptr;
}

IssueBook::IssueBook(std::string file, std::vector<Issue> issues,
                     std::function<bool(const std::string&)> supported)
    : file_(std::move(file)), supported_(std::move(supported)) {
  for (Issue& i : issues) add(std::move(i));
}

std::optional<std::string> IssueBook::ignored_extension(const Issue& issue) const {
  // Each "/extensions/NAME" on the pointer, outermost first (extension names hold no '/' or '~',
  // so the segment is the name itself).
  constexpr std::string_view kList = "/extensions/";
  const std::string& p = issue.pointer;
  for (std::size_t at = p.find(kList); at != std::string::npos; at = p.find(kList, at + 1)) {
    const std::size_t begin = at + kList.size();
    const std::size_t end = std::min(p.find('/', begin), p.size());
    std::string name = p.substr(begin, end - begin);
    if (!supported_(name)) return name;
  }
  if (issue.extensions.empty()) return std::nullopt;
  for (const std::string& name : issue.extensions)
    if (supported_(name)) return std::nullopt;
  return issue.extensions.front();
}

void IssueBook::add(Issue issue) {
  std::string key = issue.pointer;
  issues_.emplace(std::move(key), Entry{std::move(issue), false});
}

void IssueBook::use(const std::string& pointer, Log& log, bool exact) {
  for (auto it = issues_.lower_bound(pointer);
       it != issues_.end() && at_or_below(it->first, pointer); ++it) {
    if (exact && it->first != pointer) continue;
    Entry& e = it->second;
    if (e.used) continue;
    e.used = true;
    const std::string where = path_of(e.issue.pointer);
    if (const std::optional<std::string> ignored = ignored_extension(e.issue)) {
      log.warn(file_ + ": " + where + ": " + e.issue.message + "; irad ignores extension '" +
               *ignored + "'");
      continue;
    }
    if (const char* repair = repair_of(e.issue.code)) {
      log.warn(file_ + ": " + where + ": " + e.issue.message + "; " + repair);
      continue;
    }
    throw Error(file_, where, e.issue.message);
  }
}

void IssueBook::warn_unused(Log& log) const {
  std::size_t count = 0;
  const Entry* first = nullptr;
  for (const auto& [pointer, e] : issues_) {
    if (e.used) continue;
    if (!first) first = &e;
    ++count;
  }
  if (!first) return;
  const std::string where = path_of(first->issue.pointer);
  log.warn(file_ + ": " + std::to_string(count) + " problem" + (count == 1 ? "" : "s") +
           " in parts irad does not use; the first: " + (where.empty() ? "" : where + ": ") +
           first->issue.message + " (" + first->issue.code + ")");
}

} // namespace irad::gltf
