#include "core/gltf/read/skins.h"

#include "core/gltf/read/accessors.h"

#include <fmt/format.h>

namespace irad::gltf {

Skins::Skins(const Context& ctx, const std::vector<NodeInstance>& instances)
    : parent_(ctx.count("nodes"), -1) {
  if (ctx.array("skins").empty()) return;
  const json& nodes = ctx.array("nodes");
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const json* children = member(nodes[n], "children");
    if (!children || !children->is_array()) continue;
    for (const json& c : *children)
      if (const auto i = as_index(c); i && *i < nodes.size())
        parent_[std::size_t(*i)] = static_cast<long long>(n);
  }
  for (const NodeInstance& inst : instances) reached_[inst.node] = inst.world;
}

glm::dmat4 Skins::world(const Context& ctx, std::size_t node) const {
  if (const auto it = reached_.find(node); it != reached_.end()) return it->second;
  glm::dmat4 m(1.0);
  std::size_t steps = 0;
  for (long long n = static_cast<long long>(node); n >= 0; n = parent_[std::size_t(n)]) {
    if (++steps > parent_.size()) ctx.fail(element("nodes", node), "node cycle above a joint");
    m = local_matrix(ctx, std::size_t(n)) * m;
  }
  return m;
}

const SkinPose* Skins::skin_of(const Context& ctx, std::size_t node) const {
  const json& n = ctx.array("nodes")[node];
  const auto skin = optional_index(ctx, n, "skin", ctx.count("skins"), element("nodes", node));
  if (!skin) return nullptr;
  if (const auto it = cache_.find(*skin); it != cache_.end()) return &it->second;
  const json& s = ctx.at("skins", *skin, element("nodes", node), "skin");
  const std::string where = element("skins", *skin);
  const json* joints = member(s, "joints");
  if (!joints || !joints->is_array() || joints->empty()) ctx.fail(where, "no joints");
  std::vector<glm::dmat4> ibm(joints->size(), glm::dmat4(1.0));
  if (const auto a = index_member(s, "inverseBindMatrices")) {
    const Values v = read_values(ctx, *a, where + ".inverseBindMatrices", {"MAT4"}, {kFloat});
    if (v.count() != joints->size())
      ctx.fail(where, fmt::format("inverseBindMatrices has {} matrices for {} joints", v.count(),
                                  joints->size()));
    for (std::size_t j = 0; j < ibm.size(); ++j)
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) ibm[j][c][r] = double(v.data[16 * j + std::size_t(4 * c + r)]);
  }
  SkinPose out;
  for (std::size_t j = 0; j < joints->size(); ++j) {
    const auto joint = as_index((*joints)[j]);
    const std::size_t jn = checked_index(ctx, joint ? static_cast<long long>(*joint) : -1,
                                         ctx.count("nodes"), where + ".joints", "joint node");
    out.joints.push_back(jn);
    out.matrices.push_back(world(ctx, jn) * ibm[j]);
  }
  out.inverse_bind = std::move(ibm);
  return &(cache_[*skin] = std::move(out));
}

std::vector<double> morph_weights(const Context& ctx, std::size_t node, std::size_t mesh) {
  const json& m = ctx.array("meshes")[mesh];
  const json* prims = member(m, "primitives");
  std::size_t targets = 0;
  if (prims && prims->is_array())
    for (const json& p : *prims)
      if (const json* t = member(p, "targets"); t && t->is_array())
        targets = std::max(targets, t->size());
  if (targets == 0) return {};
  std::vector<double> w = numbers_member(ctx.array("nodes")[node], "weights");
  if (w.empty()) w = numbers_member(m, "weights");
  w.resize(targets, 0.0);
  return w;
}

} // namespace irad::gltf
