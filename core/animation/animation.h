#pragma once
// Node animation of a loaded scene (glTF animations of translation, rotation and scale). The
// Scene holds the triangles, cameras and lights at one time; Animation::pose(t, scene) moves the
// animated ones to time t. Every glTF animation of the file plays at once (exporters such as
// Blender write one animation per object), over [start(), end()]; outside it the first or last
// key holds.
//
// Contracts:
// - Only what moves is touched: the vertices of meshes whose node or an ancestor is animated
//   (their positions p(t) = W(t) p_local, normals n(t) = normalize(cof(W3) n_local) and
//   tangents t(t) = normalize(W3 t_local), as the loader placed them at rest), and the cameras
//   and lights on such nodes.
// - Scene::bounds does not change with t: the loader sets it to the bounds over the whole
//   animation, so every scale-relative tolerance (ray offsets, the clamp, near planes) stays
//   the same from frame to frame.
// - A scale that changes the handedness of a mesh's transform during the animation is not
//   supported (the loader rejects it at the sampled times).
#include "core/animation/keyframes.h"

#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <vector>

namespace irad {

struct Scene;

class Animation {
public:
  enum class Path { Translation, Rotation, Scale, Weights };

  struct Node {
    int parent = -1; // index into nodes, parents before children
    glm::dvec3 translation{0.0};
    glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
    glm::dvec3 scale{1.0};
    glm::dmat4 matrix{1.0}; // used instead of T R S when has_matrix (never animated)
    bool has_matrix = false;
    std::vector<double> weights; // morph target weights at rest (node.weights or mesh.weights)
  };
  struct Track {
    std::uint32_t node = 0; // index into nodes
    Path path;
    Keyframes keys;
    std::uint32_t first_weight = 0; // Weights: keys' x y z w are weights first_weight .. + 3
  };
  // The scene vertices of one animated node's meshes, in the node's frame.
  struct MeshPart {
    std::uint32_t node = 0;
    std::vector<std::uint32_t> vertices; // indices into Scene::positions
    std::vector<glm::vec3> positions;    // node-local
    std::vector<glm::vec3> normals;      // node-local (not unit: n_local = W3^T n_world)
    // Node-local tangent directions (t_local = W3^-1 t_world; Scene::tangents' w stays), or
    // empty: the scene has no tangents.
    std::vector<glm::vec3> tangents{};
  };

  // The scene vertices of one skinned or morphed mesh instance (glTF 3.7.2.2, 3.7.3), posed as
  //   p = S (p0 + sum_i w_i(t) dp_i),  S = sum_k a_k J_k(t) B_k  (skinned: joint world J,
  //   inverse bind matrix B, vertex weights a renormalised to sum 1), else S = W_node(t);
  // normals alike (n0 + sum_i w_i dn_i) by the cofactor of S, tangents (t0 + sum_i w_i dt_i) by
  // S's 3x3 block with w = w0 sign(det S). flat: the vertices come in triples of one triangle
  // each (the primitive had no NORMAL); their normal is the triangle's.
  struct DeformedPart {
    std::uint32_t node = 0;
    std::vector<std::uint32_t> vertices;                   // indices into Scene::positions
    std::vector<glm::vec3> positions;                      // mesh frame, unmorphed
    std::vector<glm::vec3> normals;                        // mesh frame, unmorphed; empty when flat
    std::vector<std::vector<glm::vec3>> position_targets;  // [target][vertex]
    std::vector<std::vector<glm::vec3>> normal_targets;    // [target][vertex], or empty
    std::vector<glm::vec4> tangents{};                     // mesh frame, unmorphed; or empty
    std::vector<std::vector<glm::vec3>> tangent_targets{}; // [target][vertex], or empty
    // Skin: per joint the index into nodes (or kFixedJoint: a joint outside the loaded
    // scene, whose J B is the constant joint_matrix); empty when not skinned.
    std::vector<std::uint32_t> joints;
    std::vector<glm::dmat4> joint_matrix; // B_k, or J_k B_k for a fixed joint
    std::vector<glm::uvec4> vertex_joints;
    std::vector<glm::vec4> vertex_weights;
    bool flat = false;
    bool flip = false; // flat triangles were stored with reversed winding
  };
  static constexpr std::uint32_t kFixedJoint = 0xFFFFFFFFu;

  std::vector<Node> nodes;
  std::vector<Track> tracks;
  std::vector<MeshPart> parts;
  std::vector<DeformedPart> deformed;
  std::vector<int> camera_node; // per Scene::cameras entry: index into nodes, or -1
  std::vector<int> light_node;  // per Scene::lights entry

  float start() const;
  float end() const;
  bool moves_geometry() const { return !parts.empty() || !deformed.empty(); }
  // Every scene vertex an animated part moves, ascending.
  std::vector<std::uint32_t> moving_vertices() const;

  // World matrices of every node at time t (parents before children).
  std::vector<glm::dmat4> world_matrices(float t) const;
  // Morph target weights of every node at time t (its rest weights, with the animated ones).
  std::vector<std::vector<double>> weights(float t) const;
  // The positions and normals of a deformed part at a pose (world matrices, node weights), and
  // its tangents into *tangents when given (empty when the part has none; unit, or 0 where S
  // takes a tangent to zero).
  void deform(const DeformedPart& part, const std::vector<glm::dmat4>& world,
              const std::vector<double>& weights, std::vector<glm::vec3>& positions,
              std::vector<glm::vec3>& normals, std::vector<glm::vec4>* tangents = nullptr) const;
  // Moves the animated vertices, cameras and lights of `scene` (as loaded with this animation)
  // to time t.
  void pose(float t, Scene& scene) const;
  // Nodes whose world matrix depends on time (animated themselves or below an animated node).
  std::vector<char> dynamic_nodes() const;
};

} // namespace irad
