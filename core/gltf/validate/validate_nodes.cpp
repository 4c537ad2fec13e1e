// Nodes (hierarchy, transforms, skin and morph weights), scenes' root nodes, and skins.
#include "core/gltf/validate/validate_semantics_read.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace irad::gltf::sem {

using nlohmann::json;

namespace {

// children[n]: node n's valid child indices, in order.
std::vector<std::vector<std::int64_t>> children_of(const Context& ctx) {
  const json& nodes = ctx.list("nodes");
  std::vector<std::vector<std::int64_t>> out(nodes.size());
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const json* ch = member(nodes[n], "children");
    if (ch == nullptr || !ch->is_array()) continue;
    for (const json& c : *ch) {
      const auto i = as_int(&c);
      out[n].push_back(i && *i >= 0 && static_cast<std::size_t>(*i) < nodes.size() ? *i : -1);
    }
  }
  return out;
}

// The first parent of each node (-1 for none).
std::vector<std::int64_t> parents_of(const std::vector<std::vector<std::int64_t>>& children) {
  std::vector<std::int64_t> parent(children.size(), -1);
  for (std::size_t p = 0; p < children.size(); ++p)
    for (std::int64_t c : children[p])
      if (c >= 0 && parent[static_cast<std::size_t>(c)] < 0)
        parent[static_cast<std::size_t>(c)] = static_cast<std::int64_t>(p);
  return parent;
}

// Nodes on a cycle of the children graph (Tarjan's strongly connected components, iterative).
std::vector<char> loop_nodes(const std::vector<std::vector<std::int64_t>>& children) {
  const std::size_t n = children.size();
  std::vector<std::int64_t> order(n, -1), low(n, 0);
  std::vector<char> on_stack(n, 0), in_loop(n, 0);
  std::vector<std::size_t> stack;
  std::int64_t counter = 0;
  for (std::size_t start = 0; start < n; ++start) {
    if (order[start] >= 0) continue;
    std::vector<std::pair<std::size_t, std::size_t>> frames = {{start, 0}};
    order[start] = low[start] = counter++;
    stack.push_back(start);
    on_stack[start] = 1;
    while (!frames.empty()) {
      auto& [v, next] = frames.back();
      if (next < children[v].size()) {
        const std::int64_t c = children[v][next++];
        if (c < 0) continue;
        const auto w = static_cast<std::size_t>(c);
        if (w == v) in_loop[v] = 1;
        if (order[w] < 0) {
          order[w] = low[w] = counter++;
          stack.push_back(w);
          on_stack[w] = 1;
          frames.emplace_back(w, 0);
        } else if (on_stack[w] != 0) {
          low[v] = std::min(low[v], order[w]);
        }
        continue;
      }
      const std::size_t done = v;
      frames.pop_back();
      if (!frames.empty()) low[frames.back().first] = std::min(low[frames.back().first], low[done]);
      if (low[done] != order[done]) continue;
      std::vector<std::size_t> component;
      std::size_t w;
      do {
        w = stack.back();
        stack.pop_back();
        on_stack[w] = 0;
        component.push_back(w);
      } while (w != done);
      if (component.size() > 1)
        for (std::size_t c : component) in_loop[c] = 1;
    }
  }
  return in_loop;
}

bool decomposable(const std::vector<double>& m) {
  if (m[3] != 0 || m[7] != 0 || m[11] != 0 || m[15] != 1) return false;
  const double* c[3] = {&m[0], &m[4], &m[8]};
  double len[3];
  for (int i = 0; i < 3; ++i)
    len[i] = std::sqrt(c[i][0] * c[i][0] + c[i][1] * c[i][1] + c[i][2] * c[i][2]);
  const double det = c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1]) -
                     c[1][0] * (c[0][1] * c[2][2] - c[0][2] * c[2][1]) +
                     c[2][0] * (c[0][1] * c[1][2] - c[0][2] * c[1][1]);
  if (!std::isfinite(det) || det == 0 || len[0] == 0 || len[1] == 0 || len[2] == 0) return false;
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) {
      const double dot = c[i][0] * c[j][0] + c[i][1] * c[j][1] + c[i][2] * c[j][2];
      if (std::fabs(dot) > 1e-3 * len[i] * len[j]) return false; // shear
    }
  return true;
}

// Morph targets of mesh m (of its first primitive), nullopt when the mesh is not there.
std::optional<std::size_t> morph_targets(const Context& ctx, std::int64_t m) {
  const json* mesh = ctx.object("meshes", m);
  const json* p0 = mesh != nullptr ? element(*mesh, "primitives", 0) : nullptr;
  if (p0 == nullptr) return std::nullopt;
  return array_size(*p0, "targets");
}

bool skinned_mesh(const Context& ctx, std::int64_t m) {
  const json* mesh = ctx.object("meshes", m);
  const json* prims = mesh != nullptr ? member(*mesh, "primitives") : nullptr;
  if (prims == nullptr || !prims->is_array()) return true; // nothing to judge
  for (const json& p : *prims) {
    const json* attrs = member(p, "attributes");
    if (attrs != nullptr && has(*attrs, "JOINTS_0") && has(*attrs, "WEIGHTS_0")) return true;
  }
  return false;
}

void check_node(const Context& ctx, const json& node, std::int64_t i) {
  const std::string ptr = at("/nodes", i);
  if (const auto m = numbers(node, "matrix"); m && m->size() == 16) {
    if (has(node, "translation") || has(node, "rotation") || has(node, "scale"))
      ctx.add(at(ptr, "matrix"), "NODE_MATRIX_TRS", "a node cannot have both matrix and TRS");
    else if (!decomposable(*m))
      ctx.add(at(ptr, "matrix"), "NODE_MATRIX_NON_TRS", "the matrix is not a TRS transform");
  }
  if (const auto q = numbers(node, "rotation"); q && q->size() == 4) {
    const double len =
        std::sqrt((*q)[0] * (*q)[0] + (*q)[1] * (*q)[1] + (*q)[2] * (*q)[2] + (*q)[3] * (*q)[3]);
    if (std::fabs(len - 1.0) > 0.0005)
      ctx.add(at(ptr, "rotation"), "ROTATION_NON_UNIT", "the rotation is not a unit quaternion");
  }
  const auto mesh = index(node, "mesh");
  if (!mesh || ctx.object("meshes", *mesh) == nullptr) return;
  if (const auto skin = index(node, "skin");
      skin && ctx.object("skins", *skin) != nullptr && !skinned_mesh(ctx, *mesh))
    ctx.add(ptr, "NODE_SKIN_WITH_NON_SKINNED_MESH", "the node has a skin but its mesh no joints");
  const json* weights = member(node, "weights");
  const auto targets = morph_targets(ctx, *mesh);
  if (weights != nullptr && weights->is_array() && targets && weights->size() != *targets)
    ctx.add(at(ptr, "weights"), "NODE_WEIGHTS_INVALID",
            "the node's weights do not match its mesh's morph targets");
}

// Skinned nodes of a scene whose skin has joints outside that scene.
void check_scene_skins(const Context& ctx, const std::vector<std::vector<std::int64_t>>& children,
                       const std::vector<std::int64_t>& roots) {
  std::vector<char> in_scene(children.size(), 0);
  std::vector<std::int64_t> todo = roots;
  while (!todo.empty()) {
    const auto n = static_cast<std::size_t>(todo.back());
    todo.pop_back();
    if (in_scene[n] != 0) continue;
    in_scene[n] = 1;
    for (std::int64_t c : children[n])
      if (c >= 0) todo.push_back(c);
  }
  for (std::size_t n = 0; n < children.size(); ++n) {
    if (in_scene[n] == 0) continue;
    const json& node = ctx.list("nodes")[n];
    const auto s = index(node, "skin");
    const json* skin = s ? ctx.object("skins", *s) : nullptr;
    const json* joints = skin != nullptr ? member(*skin, "joints") : nullptr;
    if (joints == nullptr || !joints->is_array() || !has(node, "mesh")) continue;
    for (const json& j : *joints) {
      const auto ji = as_int(&j);
      if (!ji || *ji < 0 || static_cast<std::size_t>(*ji) >= children.size()) continue;
      if (in_scene[static_cast<std::size_t>(*ji)] != 0) continue;
      ctx.add(at("/nodes", static_cast<std::int64_t>(n)), "NODE_SKIN_NO_SCENE",
              "the skinned node's scene does not contain its skin's joints");
      break;
    }
  }
}

void check_scenes(const Context& ctx, const std::vector<std::vector<std::int64_t>>& children,
                  const std::vector<std::int64_t>& parent) {
  const json& scenes = ctx.list("scenes");
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    const json* nodes = member(scenes[s], "nodes");
    if (nodes == nullptr || !nodes->is_array()) continue;
    std::vector<std::int64_t> roots;
    for (std::size_t k = 0; k < nodes->size(); ++k) {
      const auto n = as_int(&(*nodes)[k]);
      if (!n || *n < 0 || static_cast<std::size_t>(*n) >= children.size()) continue;
      roots.push_back(*n);
      if (parent[static_cast<std::size_t>(*n)] >= 0)
        ctx.add(at(at(at("/scenes", static_cast<std::int64_t>(s)), "nodes"),
                   static_cast<std::int64_t>(k)),
                "SCENE_NON_ROOT_NODE", "a scene's node must not have a parent");
    }
    check_scene_skins(ctx, children, roots);
  }
}

} // namespace

void check_nodes(const Context& ctx) {
  const auto children = children_of(ctx);
  const json& nodes = ctx.list("nodes");
  std::vector<std::int64_t> parent(children.size(), -1);
  for (std::size_t p = 0; p < children.size(); ++p)
    for (std::size_t k = 0; k < children[p].size(); ++k) {
      const std::int64_t c = children[p][k];
      if (c < 0) continue;
      auto& pc = parent[static_cast<std::size_t>(c)];
      if (pc >= 0)
        ctx.add(at(at(at("/nodes", static_cast<std::int64_t>(p)), "children"),
                   static_cast<std::int64_t>(k)),
                "NODE_PARENT_OVERRIDE", "the node already has a parent");
      else
        pc = static_cast<std::int64_t>(p);
    }
  const auto loops = loop_nodes(children);
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    if (loops[n] != 0)
      ctx.add(at("/nodes", static_cast<std::int64_t>(n)), "NODE_LOOP", "the node is in a loop");
    if (nodes[n].is_object()) check_node(ctx, nodes[n], static_cast<std::int64_t>(n));
  }
  check_scenes(ctx, children, parent);
}

namespace {

// The root above node n, following first parents (-1 when the chain loops).
std::int64_t root_of(const std::vector<std::int64_t>& parent, std::int64_t n) {
  for (std::size_t steps = 0; steps <= parent.size(); ++steps) {
    const std::int64_t p = parent[static_cast<std::size_t>(n)];
    if (p < 0) return n;
    n = p;
  }
  return -1;
}

bool is_ancestor_or_self(const std::vector<std::int64_t>& parent, std::int64_t a, std::int64_t n) {
  for (std::size_t steps = 0; steps <= parent.size() && n >= 0; ++steps) {
    if (n == a) return true;
    n = parent[static_cast<std::size_t>(n)];
  }
  return false;
}

void check_ibm(const Context& ctx, std::int64_t acc, std::size_t joints, const std::string& ptr) {
  const auto a = accessor_view(ctx, acc);
  if (!a || !a->valid) return;
  if (a->type != "MAT4" || a->component_type != kFloat) {
    ctx.add(ptr, "SKIN_IBM_INVALID_FORMAT", "inverse bind matrices must be MAT4 FLOAT");
    return;
  }
  if (a->byte_stride)
    ctx.add(ptr, "SKIN_IBM_ACCESSOR_WITH_BYTESTRIDE",
            "the inverse bind matrices' buffer view cannot have a byteStride");
  if (a->count < static_cast<std::int64_t>(joints))
    ctx.add(ptr, "INVALID_IBM_ACCESSOR_COUNT", "fewer inverse bind matrices than joints");
  const AccessorData d = read_accessor(ctx, acc);
  if (!d.ok) return;
  for (std::size_t e = 0; e + 16 <= d.values.size(); e += 16) {
    const double* m = &d.values[e];
    if (m[3] == 0 && m[7] == 0 && m[11] == 0 && m[15] == 1) continue;
    ctx.add(ptr, "ACCESSOR_INVALID_IBM", "an inverse bind matrix's last row is not (0 0 0 1)");
    return;
  }
}

void check_skin(const Context& ctx, const json& skin, std::int64_t i,
                const std::vector<std::int64_t>& parent) {
  const std::string ptr = at("/skins", i);
  const json* joints = member(skin, "joints");
  const std::size_t nj = joints != nullptr && joints->is_array() ? joints->size() : 0;
  if (const auto ibm = index(skin, "inverseBindMatrices"); ibm && ctx.object("accessors", *ibm))
    check_ibm(ctx, *ibm, nj, at(ptr, "inverseBindMatrices"));
  if (nj == 0) return;
  std::set<std::int64_t> roots;
  std::vector<std::int64_t> ids;
  for (const json& j : *joints) {
    const auto n = as_int(&j);
    const bool ok = n && *n >= 0 && static_cast<std::size_t>(*n) < parent.size();
    roots.insert(ok ? root_of(parent, *n) : -1);
    if (ok) ids.push_back(*n);
  }
  if (roots.size() != 1 || *roots.begin() < 0) {
    ctx.add(at(ptr, "joints"), "SKIN_NO_COMMON_ROOT", "the skin's joints have no common root");
    return;
  }
  const auto skeleton = index(skin, "skeleton");
  if (!skeleton || *skeleton < 0 || static_cast<std::size_t>(*skeleton) >= parent.size()) return;
  for (std::int64_t n : ids)
    if (!is_ancestor_or_self(parent, *skeleton, n)) {
      ctx.add(at(ptr, "skeleton"), "SKIN_SKELETON_INVALID",
              "the skeleton node is not above every joint");
      return;
    }
}

} // namespace

void check_skins(const Context& ctx) {
  const auto parent = parents_of(children_of(ctx));
  const json& skins = ctx.list("skins");
  for (std::size_t i = 0; i < skins.size(); ++i)
    if (skins[i].is_object()) check_skin(ctx, skins[i], static_cast<std::int64_t>(i), parent);
}

} // namespace irad::gltf::sem
