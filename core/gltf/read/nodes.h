#pragma once
// Internal to the glTF loader: the node hierarchy of the default scene, flattened.
#include "core/gltf/context.h"

#include <glm/glm.hpp>
#include <optional>
#include <vector>

namespace irad::gltf {

// A node reached from the scene's roots, with world = parent's world * local (column vectors).
struct NodeInstance {
  std::size_t node;
  glm::dmat4 world;
};

// The scene to load: `wanted` (a scene's name or index) when not empty, else the document's
// `scene`, else scene 0; nullopt when the file has no scenes. Fails when `wanted` names none.
std::optional<std::size_t> chosen_scene(const Context& ctx, const std::string& wanted);

// The local matrix of nodes[node]: its matrix (column-major), or T * R * S.
glm::dmat4 local_matrix(const Context& ctx, std::size_t node);

// The KHR_lights_punctual "lights" array of the document (empty when absent).
const json& punctual_lights(const Context& ctx);

// Flattens the chosen scene (chosen_scene(ctx, scene); without scenes: every node that is no
// node's child) depth-first, parents before children. The local matrix is node.matrix
// (column-major) or T * R * S. Fails on out-of-range scene, node, mesh, camera and light indices
// of reached nodes, on malformed transforms, on cycles, and on nodes reached twice (glTF allows
// one parent per node).
std::vector<NodeInstance> flatten_scene(const Context& ctx, const std::string& scene);

// Index of the light that nodes[node] places through its KHR_lights_punctual extension, or -1.
// Fails unless the extension holds a valid "light" index.
int node_light(const Context& ctx, std::size_t node);

} // namespace irad::gltf
