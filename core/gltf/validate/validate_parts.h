#pragma once
// Internal to core/gltf/validate/validate.cpp: its two halves. check_schema looks at the JSON alone
// (core/gltf/validate/validate_schema.cpp); check_semantics at what the JSON means and at the
// buffers' data (core/gltf/validate/validate_semantics.cpp). Both append to `issues` and never
// throw.
#include "core/gltf/validate/validate.h"

#include <nlohmann/json.hpp>

namespace irad::gltf {

void check_schema(const nlohmann::json& root, std::vector<Issue>& issues);
void check_semantics(const nlohmann::json& root, const std::vector<BufferBytes>& buffers,
                     std::vector<Issue>& issues);

} // namespace irad::gltf
