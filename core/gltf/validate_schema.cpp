#include "core/gltf/validate_parts.h"

namespace irad::gltf {

void check_schema(const nlohmann::json&, std::vector<Issue>&) {}

} // namespace irad::gltf
