#include "core/animation/animation.h"

#include "core/scene/scene.h"

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

// (normalize(A t.xyz), w sign(det A)) with A the 3x3 block of m; 0 where A t.xyz vanishes.
glm::vec4 place_tangent(const glm::dmat4& m, const glm::vec4& t) {
  const glm::dmat3 a(m);
  const glm::dvec3 d = a * glm::dvec3(glm::vec3(t));
  const double len = glm::length(d);
  if (!(len > 0.0 && std::isfinite(len))) return glm::vec4(0.0f);
  return glm::vec4(glm::vec3(d / len), glm::determinant(a) < 0.0 ? -t.w : t.w);
}

// A rigid part's tangent: xyz = normalize(W3 t_local) where that is finite and not 0; w kept
// (the loader refuses animations that change the sign of det W3).
void move_tangent(const glm::dmat4& world, const glm::vec3& local, glm::vec4& tangent) {
  const glm::vec4 t = place_tangent(world, glm::vec4(local, tangent.w));
  if (glm::vec3(t) != glm::vec3(0.0f)) tangent = glm::vec4(glm::vec3(t), tangent.w);
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
    case Path::Weights:
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

std::vector<std::vector<double>> Animation::weights(float t) const {
  std::vector<std::vector<double>> out(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) out[i] = nodes[i].weights;
  for (const Track& k : tracks) {
    if (k.path != Path::Weights) continue;
    const glm::vec4 v = k.keys.sample(t);
    std::vector<double>& w = out[k.node];
    for (std::uint32_t c = 0; c < 4; ++c)
      if (k.first_weight + c < w.size()) w[k.first_weight + c] = double(v[int(c)]);
  }
  return out;
}

std::vector<std::uint32_t> Animation::moving_vertices() const {
  std::vector<std::uint32_t> out;
  for (const MeshPart& part : parts)
    out.insert(out.end(), part.vertices.begin(), part.vertices.end());
  for (const DeformedPart& part : deformed)
    out.insert(out.end(), part.vertices.begin(), part.vertices.end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void Animation::deform(const DeformedPart& part, const std::vector<glm::dmat4>& world,
                       const std::vector<double>& w, std::vector<glm::vec3>& positions,
                       std::vector<glm::vec3>& normals, std::vector<glm::vec4>* tangents) const {
  const std::size_t n = part.vertices.size();
  positions.assign(part.positions.begin(), part.positions.end());
  normals.assign(part.normals.begin(), part.normals.end());
  if (tangents) tangents->assign(part.tangents.begin(), part.tangents.end());
  for (std::size_t i = 0; i < part.position_targets.size() && i < w.size(); ++i) {
    const float wi = float(w[i]);
    if (wi == 0.0f) continue;
    for (std::size_t k = 0; k < n; ++k) positions[k] += wi * part.position_targets[i][k];
    if (i < part.normal_targets.size() && !normals.empty())
      for (std::size_t k = 0; k < n; ++k) normals[k] += wi * part.normal_targets[i][k];
    if (tangents && i < part.tangent_targets.size() && !tangents->empty())
      for (std::size_t k = 0; k < n; ++k)
        (*tangents)[k] += glm::vec4(wi * part.tangent_targets[i][k], 0.0f);
  }
  std::vector<glm::dmat4> joint(part.joints.size());
  for (std::size_t j = 0; j < joint.size(); ++j)
    joint[j] = part.joints[j] == kFixedJoint ? part.joint_matrix[j]
                                             : world[part.joints[j]] * part.joint_matrix[j];
  for (std::size_t k = 0; k < n; ++k) {
    glm::dmat4 m = world[part.node];
    if (!joint.empty()) {
      glm::dmat4 sum(0.0);
      double total = 0.0;
      for (int c = 0; c < 4; ++c) {
        const double a = double(part.vertex_weights[k][c]);
        const std::uint32_t j = part.vertex_joints[k][c];
        if (a == 0.0 || j >= joint.size()) continue;
        sum += a * joint[j];
        total += a;
      }
      if (total > 0.0) m = sum / total;
    }
    positions[k] = glm::vec3(m * glm::dvec4(glm::dvec3(positions[k]), 1.0));
    if (!normals.empty()) {
      const glm::dvec3 nn = normal_matrix(m) * glm::dvec3(normals[k]);
      const double len = glm::length(nn);
      normals[k] = len > 0.0 && std::isfinite(len) ? glm::vec3(nn / len) : glm::vec3(0.0f);
    }
    if (tangents && !tangents->empty()) (*tangents)[k] = place_tangent(m, (*tangents)[k]);
  }
  if (!part.flat) return;
  normals.resize(n);
  for (std::size_t k = 0; k + 2 < n; k += 3) {
    glm::vec3 c = glm::cross(positions[k + 1] - positions[k], positions[k + 2] - positions[k]);
    if (part.flip) c = -c;
    const float len = glm::length(c);
    const glm::vec3 face = len > 0.0f && std::isfinite(len) ? c / len : glm::vec3(0.0f);
    normals[k] = normals[k + 1] = normals[k + 2] = face;
  }
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
      if (k < part.tangents.size() && v < scene.tangents.size())
        move_tangent(w, part.tangents[k], scene.tangents[v]);
    }
  }
  if (!deformed.empty()) {
    const std::vector<std::vector<double>> w = weights(t);
    std::vector<glm::vec3> p, n;
    std::vector<glm::vec4> tangents;
    for (const DeformedPart& part : deformed) {
      deform(part, world, w[part.node], p, n, &tangents);
      for (std::size_t k = 0; k < part.vertices.size(); ++k) {
        scene.positions[part.vertices[k]] = p[k];
        if (n[k] != glm::vec3(0.0f)) scene.normals[part.vertices[k]] = n[k];
        if (k < tangents.size() && part.vertices[k] < scene.tangents.size() &&
            glm::vec3(tangents[k]) != glm::vec3(0.0f))
          scene.tangents[part.vertices[k]] = tangents[k];
      }
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
