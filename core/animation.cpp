#include "core/animation.h"

#include "core/scene.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

namespace irad {

namespace {

// cof(A) sign(det A) = |det A| A^-T: transforms normals without inverting A.
glm::dmat3 normal_matrix(const glm::dmat4& world) {
  const glm::dmat3 a(world);
  const double det = glm::determinant(a);
  const glm::dmat3 cofactor =
      det != 0.0
          ? det * glm::transpose(glm::inverse(a))
          : glm::dmat3(glm::cross(a[1], a[2]), glm::cross(a[2], a[0]), glm::cross(a[0], a[1]));
  return det < 0.0 ? -cofactor : cofactor;
}

glm::dmat4 local_matrix(const Animation::Node& n) {
  if (n.has_matrix) return n.matrix;
  return glm::translate(glm::dmat4(1.0), n.translation) * glm::mat4_cast(n.rotation) *
         glm::scale(glm::dmat4(1.0), n.scale);
}

} // namespace

float Animation::start() const {
  float t = std::numeric_limits<float>::max();
  for (const Track& k : tracks) t = std::min(t, k.keys.start());
  return tracks.empty() ? 0.0f : t;
}

float Animation::end() const {
  float t = 0.0f;
  for (const Track& k : tracks) t = std::max(t, k.keys.end());
  return t;
}

std::vector<glm::dmat4> Animation::world_matrices(float t) const {
  std::vector<Node> posed = nodes;
  for (const Track& k : tracks) {
    const glm::vec4 v = k.keys.sample(t);
    Node& n = posed[k.node];
    switch (k.path) {
    case Path::Translation:
      n.translation = glm::dvec3(v);
      break;
    case Path::Rotation:
      n.rotation = glm::dquat(v.w, v.x, v.y, v.z);
      break;
    case Path::Scale:
      n.scale = glm::dvec3(v);
      break;
    }
  }
  std::vector<glm::dmat4> world(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const glm::dmat4 local = local_matrix(posed[i]);
    world[i] = nodes[i].parent < 0 ? local : world[std::size_t(nodes[i].parent)] * local;
  }
  return world;
}

std::vector<char> Animation::dynamic_nodes() const {
  std::vector<char> dynamic(nodes.size(), 0);
  for (const Track& k : tracks) dynamic[k.node] = 1;
  for (std::size_t i = 0; i < nodes.size(); ++i) // parents come first
    if (nodes[i].parent >= 0 && dynamic[std::size_t(nodes[i].parent)]) dynamic[i] = 1;
  return dynamic;
}

void Animation::pose(float t, Scene& scene) const {
  const std::vector<glm::dmat4> world = world_matrices(t);
  for (const MeshPart& part : parts) {
    const glm::dmat4& w = world[part.node];
    const glm::dmat3 nm = normal_matrix(w);
    for (std::size_t k = 0; k < part.vertices.size(); ++k) {
      const std::uint32_t v = part.vertices[k];
      scene.positions[v] = glm::vec3(w * glm::dvec4(glm::dvec3(part.positions[k]), 1.0));
      const glm::dvec3 n = nm * glm::dvec3(part.normals[k]);
      const double len = glm::length(n);
      if (len > 0.0 && std::isfinite(len)) scene.normals[v] = glm::vec3(n / len);
    }
  }
  for (std::size_t c = 0; c < camera_node.size() && c < scene.cameras.size(); ++c) {
    if (camera_node[c] < 0) continue;
    Camera& camera = scene.cameras[c];
    // A degenerate pose (a zero scale) keeps the previous frame.
    camera.camera_to_world =
        camera_frame_of(world[std::size_t(camera_node[c])]).value_or(camera.camera_to_world);
  }
  for (std::size_t l = 0; l < light_node.size() && l < scene.lights.size(); ++l) {
    if (light_node[l] < 0) continue;
    const glm::dmat4& w = world[std::size_t(light_node[l])];
    PunctualLight& light = scene.lights[l];
    light.position = glm::vec3(w[3]);
    const glm::dvec3 axis = -glm::dvec3(w[2]);
    const double len = glm::length(axis);
    if (len > 0.0 && std::isfinite(len)) light.direction = glm::vec3(axis / len);
  }
}

} // namespace irad
