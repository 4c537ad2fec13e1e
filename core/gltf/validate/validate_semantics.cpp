// The semantic half of the validator: what the JSON means across objects and what the buffers
// hold. The checks live in validate_semantics_*.cpp, validate_accessors.cpp,
// validate_meshes.cpp, validate_mesh_data.cpp, validate_nodes.cpp and validate_animations.cpp;
// each reads the JSON defensively (validate_semantics_read.h) and leaves wrong types, missing
// properties and unresolved indices to the schema half.
#include "core/gltf/validate/validate_parts.h"
#include "core/gltf/validate/validate_semantics_read.h"

#include <exception>
#include <iterator>
#include <thread>

namespace irad::gltf {

namespace {

// Accessors read by Draco-compressed primitives: their data is in the Draco stream, not in
// their (usually absent) bufferView, so their data is not checked.
std::vector<char> draco_accessors(const sem::Context& ctx) {
  std::vector<char> out(ctx.list("accessors").size(), 0);
  auto mark = [&](const nlohmann::json* v) {
    const auto i = sem::as_int(v);
    if (i && *i >= 0 && static_cast<std::size_t>(*i) < out.size())
      out[static_cast<std::size_t>(*i)] = 1;
  };
  for (const nlohmann::json& mesh : ctx.list("meshes")) {
    const nlohmann::json* prims = sem::member(mesh, "primitives");
    if (prims == nullptr || !prims->is_array()) continue;
    for (const nlohmann::json& prim : *prims) {
      const nlohmann::json* ext = sem::member(prim, "extensions");
      if (ext == nullptr || !sem::has(*ext, "KHR_draco_mesh_compression")) continue;
      mark(sem::member(prim, "indices"));
      if (const nlohmann::json* attrs = sem::member(prim, "attributes");
          attrs != nullptr && attrs->is_object())
        for (const auto& item : attrs->items()) mark(&item.value());
    }
  }
  return out;
}

} // namespace

void check_semantics(const nlohmann::json& root, const std::vector<BufferBytes>& buffers,
                     std::vector<Issue>& issues) {
  if (!root.is_object()) return;
  try {
    sem::Context ctx{root, buffers, issues, {}};
    ctx.draco_accessors = draco_accessors(ctx);
    sem::check_buffers(ctx);
    // The two passes over the buffers' data (a big file's bulk) on two threads, each into a list
    // of its own, appended where the checks' order puts them.
    std::vector<Issue> data_issues;
    const sem::Context data{root, buffers, data_issues, ctx.draco_accessors};
    std::exception_ptr data_failed;
    std::thread data_thread([&] {
      try {
        sem::check_mesh_data(data);
      } catch (...) {
        data_failed = std::current_exception();
      }
    });
    try {
      sem::check_accessors(ctx);
    } catch (...) {
      data_thread.join();
      throw;
    }
    data_thread.join();
    sem::check_images(ctx);
    sem::check_meshes(ctx);
    issues.insert(issues.end(), std::make_move_iterator(data_issues.begin()),
                  std::make_move_iterator(data_issues.end()));
    if (data_failed) std::rethrow_exception(data_failed);
    sem::check_nodes(ctx);
    sem::check_skins(ctx);
    sem::check_animations(ctx);
  } catch (const std::exception&) {
    // Only std::bad_alloc can reach here (every JSON read is checked); what was found stays.
  }
}

} // namespace irad::gltf
