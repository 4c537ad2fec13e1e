#include "core/gltf/validate_parts.h"

namespace irad::gltf {

void check_semantics(const nlohmann::json&, const std::vector<BufferBytes>&,
                     std::vector<Issue>&) {}

} // namespace irad::gltf
