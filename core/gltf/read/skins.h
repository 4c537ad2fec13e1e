#pragma once
// Internal to the glTF loader: skins and morph target weights at rest (no animation applied).
#include "core/gltf/context.h"
#include "core/gltf/read/nodes.h"

#include <glm/glm.hpp>
#include <map>
#include <vector>

namespace irad::gltf {

// The joint matrices of the file's skins: for skin k with joints j_0..j_n and inverse bind
// matrices B_i (identity without inverseBindMatrices), M_i = world(j_i) B_i (glTF 3.7.3), with
// world() the joint node's world matrix (from the node hierarchy, whether or not the joint is in
// the loaded scene).
struct SkinPose {
  std::vector<std::size_t> joints;      // glTF node of each joint
  std::vector<glm::dmat4> inverse_bind; // B_i
  std::vector<glm::dmat4> matrices;     // M_i = world(j_i) B_i at rest
};

class Skins {
public:
  Skins(const Context& ctx, const std::vector<NodeInstance>& instances);
  // The joint matrices for the skin of nodes[node], or nullptr when it has none. Computed on
  // first use; fails on a bad skin (joint indices, inverseBindMatrices count or type).
  const SkinPose* skin_of(const Context& ctx, std::size_t node) const;
  // world() of any node (from the hierarchy, reached or not).
  glm::dmat4 world(const Context& ctx, std::size_t node) const;

private:
  std::vector<long long> parent_; // -1 for roots
  std::map<std::size_t, glm::dmat4> reached_;
  mutable std::map<std::size_t, SkinPose> cache_;
};

// The morph target weights of mesh `mesh` drawn by nodes[node]: node.weights, else mesh.weights,
// else zeros (empty when the mesh has no targets).
std::vector<double> morph_weights(const Context& ctx, std::size_t node, std::size_t mesh);

} // namespace irad::gltf
