// Buffers, buffer views (layout and the usage each view gets from the objects that read it) and
// the headers of images stored in buffer views.
#include "core/gltf/validate/validate_semantics_read.h"

#include <map>

namespace irad::gltf::sem {

using nlohmann::json;

namespace {

constexpr std::int64_t kArrayBuffer = 34962;
constexpr std::int64_t kElementArrayBuffer = 34963;

void check_buffer(const Context& ctx, const json& b, std::int64_t i) {
  const auto length = index(b, "byteLength");
  const auto ui = static_cast<std::size_t>(i);
  const BufferBytes* bytes = ui < ctx.buffers.size() ? &ctx.buffers[ui] : nullptr;
  const std::string ptr = at("/buffers", i);
  // Assumption (see BufferBytes::glb_without_bin): the caller flags buffer 0 of a GLB without
  // a BIN chunk; a meshopt fallback buffer has no data by design.
  const json* ext = member(b, "extensions");
  const bool fallback = ext != nullptr && has(*ext, "EXT_meshopt_compression");
  if (i == 0 && !has(b, "uri") && !fallback && bytes != nullptr && bytes->glb_without_bin &&
      !bytes->present) {
    ctx.add(ptr, "BUFFER_MISSING_GLB_DATA", "buffer 0 has no uri and the GLB has no BIN chunk");
    return;
  }
  if (length && bytes != nullptr && bytes->present &&
      static_cast<std::uint64_t>(*length) > bytes->size)
    ctx.add(ptr, "BUFFER_BYTE_LENGTH_MISMATCH",
            "the buffer has " + std::to_string(bytes->size) + " bytes, fewer than its byteLength " +
                std::to_string(*length));
}

void check_buffer_view(const Context& ctx, const json& bv, std::int64_t i) {
  const std::string ptr = at("/bufferViews", i);
  const auto buffer = index(bv, "buffer");
  const auto length = index(bv, "byteLength");
  const std::int64_t offset = index(bv, "byteOffset").value_or(0);
  const json* b = buffer ? ctx.object("buffers", *buffer) : nullptr;
  const auto buffer_length = b != nullptr ? index(*b, "byteLength") : std::nullopt;
  if (length && buffer_length && sane(offset) && sane(*length) && sane(*buffer_length)) {
    if (offset >= *buffer_length && *length > 0)
      ctx.add(at(ptr, "byteOffset"), "BUFFER_VIEW_TOO_LONG",
              "the view starts past the end of its buffer");
    else if (offset + *length > *buffer_length)
      ctx.add(at(ptr, "byteLength"), "BUFFER_VIEW_TOO_LONG",
              "the view ends past the end of its buffer");
  }
  const auto stride = index(bv, "byteStride");
  if (stride && length && *stride > *length)
    ctx.add(at(ptr, "byteStride"), "BUFFER_VIEW_TOO_BIG_BYTE_STRIDE",
            "byteStride is greater than byteLength");
  if (stride && index(bv, "target") == kElementArrayBuffer)
    ctx.add(at(ptr, "byteStride"), "BUFFER_VIEW_INVALID_BYTE_STRIDE",
            "an index buffer view cannot have a byteStride");
}

enum class Usage { Vertex, Index, Other };

const char* usage_name(Usage u) {
  switch (u) {
  case Usage::Vertex:
    return "vertex data";
  case Usage::Index:
    return "index data";
  default:
    return "non-vertex data";
  }
}

// The usage of each buffer view, set by the first object that reads it (or its target).
class Usages {
public:
  explicit Usages(const Context& ctx) : ctx_(ctx) {
    const json& views = ctx.list("bufferViews");
    for (std::size_t i = 0; i < views.size(); ++i) {
      const auto target = index(views[i], "target");
      if (target == kArrayBuffer) usage_[static_cast<std::int64_t>(i)] = Usage::Vertex;
      if (target == kElementArrayBuffer) usage_[static_cast<std::int64_t>(i)] = Usage::Index;
    }
  }
  // Records that the view of accessor `acc` is read as `u` by the element at `pointer`.
  void accessor(std::optional<std::int64_t> acc, Usage u, const std::string& pointer) {
    const json* a = acc ? ctx_.object("accessors", *acc) : nullptr;
    if (a != nullptr) view(index(*a, "bufferView"), u, pointer);
  }
  void view(std::optional<std::int64_t> v, Usage u, const std::string& pointer) {
    if (!v || ctx_.object("bufferViews", *v) == nullptr) return;
    auto [it, inserted] = usage_.emplace(*v, u);
    if (!inserted && it->second != u)
      ctx_.add(pointer, "BUFFER_VIEW_TARGET_OVERRIDE",
               std::string("the buffer view was used for ") + usage_name(it->second) +
                   ", now for " + usage_name(u));
  }

private:
  const Context& ctx_;
  std::map<std::int64_t, Usage> usage_;
};

void sparse_usages(const Context& ctx, Usages& usages) {
  const json& accessors = ctx.list("accessors");
  for (std::size_t i = 0; i < accessors.size(); ++i) {
    const json* sparse = member(accessors[i], "sparse");
    if (sparse == nullptr) continue;
    const std::string ptr = at(at("/accessors", static_cast<std::int64_t>(i)), "sparse");
    for (const char* part : {"indices", "values"}) {
      const json* p = member(*sparse, part);
      if (p == nullptr) continue;
      const auto v = index(*p, "bufferView");
      const std::string vp = at(at(ptr, part), "bufferView");
      usages.view(v, Usage::Other, vp);
      const json* bv = v ? ctx.object("bufferViews", *v) : nullptr;
      if (bv != nullptr && has(*bv, "byteStride"))
        ctx.add(vp, "BUFFER_VIEW_INVALID_BYTE_STRIDE",
                "a sparse accessor's view cannot have a byteStride");
    }
  }
}

void mesh_usages(const Context& ctx, Usages& usages) {
  const json& meshes = ctx.list("meshes");
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const json* prims = member(meshes[m], "primitives");
    if (prims == nullptr || !prims->is_array()) continue;
    for (std::size_t p = 0; p < prims->size(); ++p) {
      const json& prim = (*prims)[p];
      const json* ext = member(prim, "extensions");
      if (ext != nullptr && has(*ext, "KHR_draco_mesh_compression")) continue;
      const std::string ptr = at(at(at("/meshes", static_cast<std::int64_t>(m)), "primitives"),
                                 static_cast<std::int64_t>(p));
      if (const json* attrs = member(prim, "attributes"); attrs && attrs->is_object())
        for (const auto& [name, acc] : attrs->items())
          usages.accessor(as_int(&acc), Usage::Vertex, at(at(ptr, "attributes"), name));
      usages.accessor(index(prim, "indices"), Usage::Index, at(ptr, "indices"));
      const json* targets = member(prim, "targets");
      if (targets == nullptr || !targets->is_array()) continue;
      for (std::size_t t = 0; t < targets->size(); ++t) {
        if (!(*targets)[t].is_object()) continue;
        for (const auto& [name, acc] : (*targets)[t].items())
          usages.accessor(as_int(&acc), Usage::Vertex,
                          at(at(at(ptr, "targets"), static_cast<std::int64_t>(t)), name));
      }
    }
  }
}

} // namespace

void check_buffers(const Context& ctx) {
  const json& buffers = ctx.list("buffers");
  for (std::size_t i = 0; i < buffers.size(); ++i)
    if (buffers[i].is_object()) check_buffer(ctx, buffers[i], static_cast<std::int64_t>(i));
  const json& views = ctx.list("bufferViews");
  for (std::size_t i = 0; i < views.size(); ++i)
    if (views[i].is_object()) check_buffer_view(ctx, views[i], static_cast<std::int64_t>(i));
  Usages usages(ctx);
  sparse_usages(ctx, usages);
  mesh_usages(ctx, usages);
}

} // namespace irad::gltf::sem
