#pragma once
// Internal to the glTF loader: the node hierarchy of the default scene, flattened.
#include "core/gltf/context.h"

#include <glm/glm.hpp>
#include <vector>

namespace irad::gltf {

// A node reached from the scene's roots, with world = parent's world * local (column vectors).
struct NodeInstance {
  std::size_t node;
  glm::dmat4 world;
};

// Flattens the default scene (model.defaultScene, else scene 0, else every node that is no
// node's child) depth-first, parents before children. The local matrix is node.matrix
// (column-major) or T * R * S. Fails on out-of-range scene, node, mesh, camera and light indices
// of reached nodes, on malformed transforms, on cycles, and on nodes reached twice (glTF allows
// one parent per node).
std::vector<NodeInstance> flatten_scene(const Context& ctx);

// Index of the light that nodes[node] places through its KHR_lights_punctual extension, or -1.
// Fails unless the extension holds a valid "light" index.
int node_light(const Context& ctx, std::size_t node);

} // namespace irad::gltf
