#pragma once
// Internal to the glTF loader: model.animations to an irad::Animation over the default scene.
#include "core/animation/animation.h"
#include "core/gltf/context.h"
#include "core/gltf/read/geometry.h"
#include "core/gltf/read/nodes.h"
#include "core/scene/scene.h"

#include <memory>
#include <vector>

namespace irad::gltf {

// Where the loader put each node's content: the glTF node of every scene vertex, camera and light.
struct ContentNodes {
  std::vector<std::uint32_t> vertex_node;
  std::vector<Soup::Deform> deforms; // skinned and morphed primitives (scene vertices)
  std::vector<std::size_t> camera_node;
  std::vector<std::size_t> light_node;
};

// The file's animations (all of them, played together) over the reached nodes `instances` (as
// flatten_scene gives them, at rest), or nullptr when no channel targets a reached node. Widens
// scene.bounds to the bounds over the animation. Fails on a bad sampler or channel: indices out
// of range, an unknown path or interpolation, input times not finite, negative or not strictly
// increasing, outputs of the wrong type or count, a zero rotation quaternion, an animated node
// with a matrix, and a scale that mirrors a mesh during the animation. Skinned and morphed
// meshes whose joints or weights are animated become Animation::DeformedPart (content.deforms
// is consumed). KHR_animation_pointer channels are ignored with a warning.
std::shared_ptr<const Animation> read_animation(const Context& ctx,
                                                const std::vector<NodeInstance>& instances,
                                                ContentNodes& content, Scene& scene);

} // namespace irad::gltf
