#pragma once
// Node animation of a loaded scene (glTF animations of translation, rotation and scale). The
// Scene holds the triangles, cameras and lights at one time; Animation::pose(t, scene) moves the
// animated ones to time t. Every glTF animation of the file plays at once (exporters such as
// Blender write one animation per object), over [start(), end()]; outside it the first or last
// key holds.
//
// Contracts:
// - Only what moves is touched: the vertices of meshes whose node or an ancestor is animated
//   (their positions p(t) = W(t) p_local and normals n(t) = normalize(cof(W3) n_local), as the
//   loader placed them at rest), and the cameras and lights on such nodes.
// - Scene::bounds does not change with t: the loader sets it to the bounds over the whole
//   animation, so every scale-relative tolerance (ray offsets, the clamp, near planes) stays
//   the same from frame to frame.
// - A scale that changes the handedness of a mesh's transform during the animation is not
//   supported (the loader rejects it at the sampled times).
#include "core/keyframes.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <vector>

namespace irad {

struct Scene;

class Animation {
public:
  enum class Path { Translation, Rotation, Scale };

  struct Node {
    int parent = -1; // index into nodes, parents before children
    glm::dvec3 translation{0.0};
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
    glm::dvec3 scale{1.0};
    glm::dmat4 matrix{1.0}; // used instead of T R S when has_matrix (never animated)
    bool has_matrix = false;
  };
  struct Track {
    std::uint32_t node; // index into nodes
    Path path;
    Keyframes keys;
  };
  // The scene vertices of one animated node's meshes, in the node's frame.
  struct MeshPart {
    std::uint32_t node;
    std::vector<std::uint32_t> vertices; // indices into Scene::positions
    std::vector<glm::vec3> positions;    // node-local
    std::vector<glm::vec3> normals;      // node-local (not unit: n_local = W3^T n_world)
  };

  std::vector<Node> nodes;
  std::vector<Track> tracks;
  std::vector<MeshPart> parts;
  std::vector<int> camera_node; // per Scene::cameras entry: index into nodes, or -1
  std::vector<int> light_node;  // per Scene::lights entry

  float start() const;
  float end() const;
  bool moves_geometry() const { return !parts.empty(); }

  // World matrices of every node at time t (parents before children).
  std::vector<glm::dmat4> world_matrices(float t) const;
  // Moves the animated vertices, cameras and lights of `scene` (as loaded with this animation)
  // to time t.
  void pose(float t, Scene& scene) const;
  // Nodes whose world matrix depends on time (animated themselves or below an animated node).
  std::vector<char> dynamic_nodes() const;
};

} // namespace irad
