#include "core/gltf/read/nodes.h"

#include <cmath>
#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

namespace irad::gltf {

namespace {

void require_finite(const Context& ctx, const std::vector<double>& values, const std::string& where,
                    const char* field) {
  for (double v : values) {
    if (!std::isfinite(v)) ctx.fail(where, std::string(field) + " has a non-finite component");
  }
}

void require_size(const Context& ctx, const std::vector<double>& values, std::size_t size,
                  const std::string& where, const char* field) {
  if (!values.empty() && values.size() != size) {
    ctx.fail(where, std::string(field) + " must have " + std::to_string(size) + " components");
  }
  require_finite(ctx, values, where, field);
}

// node.matrix, column-major; it must be affine (bottom row 0 0 0 1).
glm::dmat4 matrix_of(const Context& ctx, const std::vector<double>& matrix,
                     const std::string& where) {
  require_size(ctx, matrix, 16, where, "matrix");
  glm::dmat4 m(1.0);
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) m[c][r] = matrix[std::size_t(4 * c + r)];
  }
  if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0) {
    ctx.fail(where, "matrix must be affine (last row 0 0 0 1)");
  }
  return m;
}

// T * R * S from translation, rotation (unit quaternion x, y, z, w; renormalised) and scale.
glm::dmat4 trs_of(const Context& ctx, const json& n, const std::string& where) {
  const std::vector<double> t = numbers_member(n, "translation");
  const std::vector<double> r = numbers_member(n, "rotation");
  const std::vector<double> s = numbers_member(n, "scale");
  require_size(ctx, t, 3, where, "translation");
  require_size(ctx, r, 4, where, "rotation");
  require_size(ctx, s, 3, where, "scale");
  glm::dmat4 m(1.0);
  if (!t.empty()) m = glm::translate(m, glm::dvec3(t[0], t[1], t[2]));
  if (!r.empty()) {
    const glm::dquat q(r[3], r[0], r[1], r[2]); // w, x, y, z
    const double len = glm::length(q);
    if (!(len > 0.0)) ctx.fail(where, "rotation must be a non-zero quaternion");
    m = m * glm::mat4_cast(q / len);
  }
  if (!s.empty()) m = glm::scale(m, glm::dvec3(s[0], s[1], s[2]));
  return m;
}

} // namespace

glm::dmat4 local_matrix(const Context& ctx, std::size_t node) {
  const json& n = ctx.array("nodes")[node];
  const std::string where = element("nodes", node);
  const std::vector<double> matrix = numbers_member(n, "matrix");
  if (member(n, "matrix")) return matrix_of(ctx, matrix, where);
  return trs_of(ctx, n, where);
}

namespace {

// Checks the indices a reached node refers to.
void check_node(const Context& ctx, std::size_t node) {
  const json& n = ctx.array("nodes")[node];
  const std::string where = element("nodes", node);
  ctx.use("nodes", node);
  optional_index(ctx, n, "mesh", ctx.count("meshes"), where);
  optional_index(ctx, n, "camera", ctx.count("cameras"), where);
  optional_index(ctx, n, "skin", ctx.count("skins"), where);
  node_light(ctx, node);
}

// The node indices of array `key` of `object` (children, scene nodes), each checked.
std::vector<std::size_t> index_list(const Context& ctx, const json& object, const char* key,
                                    std::size_t size, const std::string& where,
                                    const std::string& what) {
  std::vector<std::size_t> out;
  const json* list = member(object, key);
  if (!list) return out;
  if (!list->is_array()) ctx.fail(where, std::string(key) + " must be an array");
  for (const json& v : *list) {
    const auto i = as_index(v);
    out.push_back(checked_index(ctx, i ? static_cast<long long>(*i) : -1, size, where, what));
  }
  return out;
}

// Root nodes of the scene to load.
std::vector<std::size_t> scene_roots(const Context& ctx, const std::string& wanted) {
  const std::size_t nodes = ctx.count("nodes");
  if (const auto scene = chosen_scene(ctx, wanted)) {
    const std::string where = element("scenes", *scene);
    ctx.use("scenes", *scene);
    return index_list(ctx, ctx.array("scenes")[*scene], "nodes", nodes, where, "node");
  }
  std::vector<char> is_child(nodes, 0);
  for (const json& n : ctx.array("nodes")) {
    const json* children = member(n, "children");
    if (!children || !children->is_array()) continue;
    for (const json& c : *children) {
      const auto i = as_index(c);
      if (i && *i < nodes) is_child[std::size_t(*i)] = 1;
    }
  }
  std::vector<std::size_t> roots;
  for (std::size_t i = 0; i < nodes; ++i) {
    if (!is_child[i]) roots.push_back(i);
  }
  return roots;
}

// Depth-first traversal with an explicit stack (deep hierarchies cannot overflow the call stack).
class Flattener {
public:
  explicit Flattener(const Context& ctx)
      : ctx_(ctx), on_path_(ctx.count("nodes"), 0), reached_(ctx.count("nodes"), 0) {}

  std::vector<NodeInstance> run(const std::string& scene) {
    for (std::size_t root : scene_roots(ctx_, scene)) {
      enter(root, glm::dmat4(1.0));
      while (!stack_.empty()) step();
    }
    return std::move(out_);
  }

private:
  struct Frame {
    std::size_t node;
    glm::dmat4 world;
    std::vector<std::size_t> children;
    std::size_t next_child;
  };

  void enter(std::size_t node, const glm::dmat4& parent) {
    const std::string where = element("nodes", node);
    if (on_path_[node]) ctx_.fail(where, "node cycle: " + where + " is its own ancestor");
    if (reached_[node]) ctx_.fail(where, "node reached twice (more than one parent)");
    check_node(ctx_, node);
    on_path_[node] = reached_[node] = 1;
    const glm::dmat4 world = parent * local_matrix(ctx_, node);
    out_.push_back({node, world});
    stack_.push_back({node, world,
                      index_list(ctx_, ctx_.array("nodes")[node], "children", on_path_.size(),
                                 where, "child node"),
                      0});
  }

  void step() {
    Frame& top = stack_.back();
    if (top.next_child == top.children.size()) {
      on_path_[top.node] = 0;
      stack_.pop_back();
      return;
    }
    const std::size_t child = top.children[top.next_child++];
    const glm::dmat4 world = top.world; // `top` dangles once enter() grows the stack
    enter(child, world);
  }

  const Context& ctx_;
  std::vector<char> on_path_;
  std::vector<char> reached_;
  std::vector<Frame> stack_;
  std::vector<NodeInstance> out_;
};

} // namespace

std::vector<NodeInstance> flatten_scene(const Context& ctx, const std::string& scene) {
  return Flattener(ctx).run(scene);
}

std::optional<std::size_t> chosen_scene(const Context& ctx, const std::string& wanted) {
  const json& scenes = ctx.array("scenes");
  if (!wanted.empty()) {
    for (std::size_t i = 0; i < scenes.size(); ++i)
      if (string_member(scenes[i], "name") == wanted) return i;
    const bool digits = wanted.find_first_not_of("0123456789") == std::string::npos;
    if (digits && wanted.size() < 10 && std::stoull(wanted) < scenes.size())
      return std::size_t(std::stoull(wanted));
    ctx.fail("scenes",
             fmt::format("no scene named or numbered '{}' ({} scenes)", wanted, scenes.size()));
  }
  if (const json* s = member(ctx.root, "scene")) {
    const auto i = as_index(*s);
    return checked_index(ctx, i ? static_cast<long long>(*i) : -1, scenes.size(), "scene", "scene");
  }
  if (!scenes.empty()) return 0;
  return std::nullopt;
}

// The lights of KHR_lights_punctual (the document extension's "lights" array).
const json& punctual_lights(const Context& ctx) {
  static const json kEmpty = json::array();
  const json* ext = extension(ctx.root, "KHR_lights_punctual");
  const json* lights = ext ? member(*ext, "lights") : nullptr;
  return lights && lights->is_array() ? *lights : kEmpty;
}

int node_light(const Context& ctx, std::size_t node) {
  const json* ext = extension(ctx.array("nodes")[node], "KHR_lights_punctual");
  if (!ext) return -1;
  const std::string where = element("nodes", node) + ".extensions.KHR_lights_punctual";
  const auto index = index_member(*ext, "light");
  const std::size_t count = punctual_lights(ctx).size();
  if (!index || *index >= count) {
    ctx.fail(where, fmt::format("light index out of range ({} lights)", count));
  }
  ctx.use("/extensions/KHR_lights_punctual/lights/" + std::to_string(*index));
  return int(*index);
}

} // namespace irad::gltf
