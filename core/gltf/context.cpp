#include "core/gltf/context.h"

namespace irad::gltf {

std::optional<std::size_t> optional_index(const Context& ctx, const json& object, const char* key,
                                          std::size_t size, const std::string& where) {
  const json* v = member(object, key);
  if (!v) return std::nullopt;
  const auto i = as_index(*v);
  return checked_index(ctx, i ? static_cast<long long>(*i) : -1, size, where, key);
}

} // namespace irad::gltf
