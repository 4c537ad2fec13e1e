#include "core/gltf/validate/validate.h"

#include "core/gltf/validate/validate_parts.h"

#include <algorithm>

namespace irad::gltf {

std::vector<Issue> validate(const nlohmann::json& root, const std::vector<BufferBytes>& buffers) {
  std::vector<Issue> issues;
  if (!root.is_object()) {
    issues.push_back({"", "TYPE_MISMATCH", "the document is not a JSON object"});
    return issues;
  }
  check_schema(root, issues);
  check_semantics(root, buffers, issues);
  // Document order: by pointer, so that the first issue of an element is the one reported.
  std::stable_sort(issues.begin(), issues.end(),
                   [](const Issue& a, const Issue& b) { return a.pointer < b.pointer; });
  return issues;
}

} // namespace irad::gltf
