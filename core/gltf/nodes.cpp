#include "core/gltf/nodes.h"

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
glm::dmat4 matrix_of(const Context& ctx, const tinygltf::Node& n, const std::string& where) {
  require_size(ctx, n.matrix, 16, where, "matrix");
  glm::dmat4 m(1.0);
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) m[c][r] = n.matrix[std::size_t(4 * c + r)];
  }
  if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0) {
    ctx.fail(where, "matrix must be affine (last row 0 0 0 1)");
  }
  return m;
}

// T * R * S from translation, rotation (unit quaternion x, y, z, w; renormalised) and scale.
glm::dmat4 trs_of(const Context& ctx, const tinygltf::Node& n, const std::string& where) {
  require_size(ctx, n.translation, 3, where, "translation");
  require_size(ctx, n.rotation, 4, where, "rotation");
  require_size(ctx, n.scale, 3, where, "scale");
  glm::dmat4 m(1.0);
  if (!n.translation.empty()) {
    m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
  }
  if (!n.rotation.empty()) {
    const glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]); // w, x, y, z
    const double len = glm::length(q);
    if (!(len > 0.0)) ctx.fail(where, "rotation must be a non-zero quaternion");
    m = m * glm::mat4_cast(q / len);
  }
  if (!n.scale.empty()) m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  return m;
}

glm::dmat4 local_matrix(const Context& ctx, std::size_t node) {
  const tinygltf::Node& n = ctx.model.nodes[node];
  const std::string where = element("nodes", node);
  if (!n.matrix.empty()) return matrix_of(ctx, n, where);
  return trs_of(ctx, n, where);
}

// Checks the indices a reached node refers to.
void check_node(const Context& ctx, std::size_t node) {
  const tinygltf::Node& n = ctx.model.nodes[node];
  const std::string where = element("nodes", node);
  if (n.mesh != -1) checked_index(ctx, n.mesh, ctx.model.meshes.size(), where, "mesh");
  if (n.camera != -1) checked_index(ctx, n.camera, ctx.model.cameras.size(), where, "camera");
  node_light(ctx, node);
  if (n.skin != -1) ctx.warn(where + ": skins are not supported; the mesh is used unskinned");
}

// Root nodes of the scene to load.
std::vector<std::size_t> scene_roots(const Context& ctx) {
  const auto& model = ctx.model;
  std::vector<std::size_t> roots;
  if (model.defaultScene >= 0 || !model.scenes.empty()) {
    const int s = model.defaultScene >= 0 ? model.defaultScene : 0;
    const std::size_t scene = checked_index(ctx, s, model.scenes.size(), "scene", "scene");
    for (int n : model.scenes[scene].nodes) {
      roots.push_back(checked_index(ctx, n, model.nodes.size(), element("scenes", scene), "node"));
    }
    return roots;
  }
  std::vector<char> is_child(model.nodes.size(), 0);
  for (const tinygltf::Node& n : model.nodes) {
    for (int c : n.children) {
      if (c >= 0 && std::size_t(c) < model.nodes.size()) is_child[std::size_t(c)] = 1;
    }
  }
  for (std::size_t i = 0; i < model.nodes.size(); ++i) {
    if (!is_child[i]) roots.push_back(i);
  }
  return roots;
}

// Depth-first traversal with an explicit stack (deep hierarchies cannot overflow the call stack).
class Flattener {
public:
  explicit Flattener(const Context& ctx)
      : ctx_(ctx), on_path_(ctx.model.nodes.size(), 0), reached_(ctx.model.nodes.size(), 0) {}

  std::vector<NodeInstance> run() {
    for (std::size_t root : scene_roots(ctx_)) {
      enter(root, glm::dmat4(1.0));
      while (!stack_.empty()) step();
    }
    return std::move(out_);
  }

private:
  struct Frame {
    std::size_t node;
    glm::dmat4 world;
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
    stack_.push_back({node, world, 0});
  }

  void step() {
    Frame& top = stack_.back();
    const std::vector<int>& children = ctx_.model.nodes[top.node].children;
    if (top.next_child == children.size()) {
      on_path_[top.node] = 0;
      stack_.pop_back();
      return;
    }
    const int child = children[top.next_child++];
    const glm::dmat4 world = top.world; // `top` dangles once enter() grows the stack
    enter(checked_index(ctx_, child, ctx_.model.nodes.size(), element("nodes", top.node),
                        "child node"),
          world);
  }

  const Context& ctx_;
  std::vector<char> on_path_;
  std::vector<char> reached_;
  std::vector<Frame> stack_;
  std::vector<NodeInstance> out_;
};

} // namespace

std::vector<NodeInstance> flatten_scene(const Context& ctx) {
  return Flattener(ctx).run();
}

int node_light(const Context& ctx, std::size_t node) {
  const tinygltf::Node& n = ctx.model.nodes[node];
  const auto ext = n.extensions.find("KHR_lights_punctual");
  if (ext == n.extensions.end()) return -1;
  const std::string where = element("nodes", node);
  const tinygltf::Value& v = ext->second;
  if (!v.IsObject() || !v.Has("light") || !v.Get("light").IsNumber()) {
    ctx.fail(where, "KHR_lights_punctual must hold a light index");
  }
  const double index = v.Get("light").GetNumberAsDouble();
  const std::size_t count = ctx.model.lights.size();
  if (!(index >= 0.0 && index < double(count)) || index != std::floor(index)) {
    ctx.fail(where, fmt::format("light index {} out of range ({} lights)", index, count));
  }
  return int(index);
}

} // namespace irad::gltf
