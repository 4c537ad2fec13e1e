#include "core/gltf/read/animation.h"

#include "core/gltf/read/skins.h"

#include "core/gltf/read/accessors.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <set>

namespace irad::gltf {

namespace {

constexpr int kUniformSamples = 64; // bounds: sampled times besides every key time

Interpolation interpolation_of(const Context& ctx, const std::string& name,
                               const std::string& where) {
  if (name.empty() || name == "LINEAR") return Interpolation::Linear;
  if (name == "STEP") return Interpolation::Step;
  if (name == "CUBICSPLINE") return Interpolation::CubicSpline;
  ctx.fail(where, "unknown interpolation '" + name + "'");
}

std::vector<float> read_times(const Context& ctx, std::uint64_t accessor,
                              const std::string& where) {
  const std::vector<glm::vec4> v = read_animation_values(ctx, accessor, where + ".input", "SCALAR");
  std::vector<float> times(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    times[i] = v[i].x;
    if (times[i] < 0.0f) ctx.fail(where, fmt::format("input time {} is negative", times[i]));
    if (i > 0 && !(times[i] > times[i - 1])) {
      ctx.warn(where + fmt::format(": input times do not increase ({} after {}); the channel is "
                                   "ignored",
                                   times[i], times[i - 1]));
      return {};
    }
  }
  return times;
}

// The sampler of animations[a] that `channel` refers to, after use(); `where` gets its path.
const json& sampler_of(const Context& ctx, std::size_t a, const json& channel, std::string& where) {
  const std::string owner = element("animations", a);
  const json* samplers = member(ctx.array("animations")[a], "samplers");
  const std::size_t count = samplers && samplers->is_array() ? samplers->size() : 0;
  const auto s = index_member(channel, "sampler");
  const std::size_t si =
      checked_index(ctx, s ? static_cast<long long>(*s) : -1, count, owner, "sampler");
  where = owner + element(".samplers", si);
  ctx.use(pointer_of("animations", a) + "/samplers/" + std::to_string(si));
  return (*samplers)[si];
}

// The keyframes of the sampler of `channel` (of animation `a`) for `path`.
Keyframes read_keyframes(const Context& ctx, std::size_t a, const json& channel,
                         Animation::Path path) {
  std::string where;
  const json& sampler = sampler_of(ctx, a, channel, where);
  Keyframes k;
  k.interpolation = interpolation_of(ctx, string_member(sampler, "interpolation"), where);
  k.rotation = path == Animation::Path::Rotation;
  k.times = read_times(ctx, index_member(sampler, "input").value_or(~0ull >> 1), where);
  if (k.times.empty()) return k; // ignored (read_times warned)
  k.values = read_animation_values(ctx, index_member(sampler, "output").value_or(~0ull >> 1),
                                   where + ".output", k.rotation ? "VEC4" : "VEC3");
  const std::size_t per_key = k.interpolation == Interpolation::CubicSpline ? 3 : 1;
  if (k.values.size() != per_key * k.times.size())
    ctx.fail(where, fmt::format("output has {} elements, {} expected ({} keys)", k.values.size(),
                                per_key * k.times.size(), k.times.size()));
  if (k.rotation && per_key == 1) {
    for (glm::vec4& q : k.values) {
      const float len = glm::length(q);
      if (!(len > 1e-6f)) ctx.fail(where, "a rotation output is a zero quaternion");
      q /= len;
    }
  }
  return k;
}

Animation::Node node_at_rest(const Context& ctx, std::size_t n) {
  const json& node = ctx.array("nodes")[n];
  Animation::Node out;
  const std::vector<double> t = numbers_member(node, "translation");
  const std::vector<double> r = numbers_member(node, "rotation");
  const std::vector<double> s = numbers_member(node, "scale");
  const std::vector<double> matrix = numbers_member(node, "matrix");
  if (t.size() == 3) out.translation = {t[0], t[1], t[2]};
  if (r.size() == 4) out.rotation = glm::normalize(glm::dquat(r[3], r[0], r[1], r[2]));
  if (s.size() == 3) out.scale = {s[0], s[1], s[2]};
  if (matrix.size() == 16) {
    out.has_matrix = true;
    for (int c = 0; c < 4; ++c)
      for (int row = 0; row < 4; ++row) out.matrix[c][row] = matrix[std::size_t(4 * c + row)];
  }
  return out;
}

// The world matrix of any glTF node from the hierarchy at rest (parents found by search).
glm::dmat4 local_world(const Context& ctx, std::size_t node) {
  const json& nodes = ctx.array("nodes");
  glm::dmat4 m = local_matrix(ctx, node);
  std::size_t current = node;
  for (std::size_t steps = 0; steps < nodes.size(); ++steps) {
    std::optional<std::size_t> parent;
    for (std::size_t p = 0; p < nodes.size() && !parent; ++p) {
      const json* children = member(nodes[p], "children");
      if (!children || !children->is_array()) continue;
      for (const json& c : *children)
        if (as_index(c) == current) parent = p;
    }
    if (!parent) break;
    m = local_matrix(ctx, *parent) * m;
    current = *parent;
  }
  return m;
}

// A weights channel of a node with N morph targets: outputs hold N weights per key (3 N for
// CUBICSPLINE: in-tangents, values, out-tangents), split into tracks of four weights each.
void read_weight_tracks(const Context& ctx, std::size_t a, const json& channel, std::uint32_t node,
                        Animation& out) {
  const std::size_t n = out.nodes[node].weights.size();
  const std::string owner = element("animations", a);
  if (n == 0) {
    ctx.warn(owner + ": a weights channel targets a node without morph targets; ignored");
    return;
  }
  std::string where;
  const json& sampler = sampler_of(ctx, a, channel, where);
  const Interpolation interpolation =
      interpolation_of(ctx, string_member(sampler, "interpolation"), where);
  const std::vector<float> times =
      read_times(ctx, index_member(sampler, "input").value_or(~0ull >> 1), where);
  if (times.empty()) return;
  const std::vector<glm::vec4> v = read_animation_values(
      ctx, index_member(sampler, "output").value_or(~0ull >> 1), where + ".output", "SCALAR");
  const std::size_t per_key = interpolation == Interpolation::CubicSpline ? 3 : 1;
  if (v.size() != per_key * n * times.size())
    ctx.fail(where, fmt::format("output has {} elements, {} expected ({} keys x {} weights)",
                                v.size(), per_key * n * times.size(), times.size(), n));
  for (std::size_t first = 0; first < n; first += 4) {
    Keyframes k;
    k.interpolation = interpolation;
    k.times = times;
    k.values.resize(per_key * times.size(), glm::vec4(0.0f));
    for (std::size_t e = 0; e < k.values.size(); ++e)
      for (std::size_t c = 0; c < 4 && first + c < n; ++c)
        k.values[e][int(c)] = v[e * n + first + c].x;
    out.tracks.push_back({node, Animation::Path::Weights, std::move(k), std::uint32_t(first)});
  }
}

Animation::Path animation_path(const std::string& path) {
  if (path == "translation") return Animation::Path::Translation;
  if (path == "rotation") return Animation::Path::Rotation;
  return Animation::Path::Scale;
}

// The tracks of every channel targeting a reached node (`index` maps glTF node -> nodes).
void read_tracks(const Context& ctx, const std::map<std::size_t, std::uint32_t>& index,
                 Animation& out) {
  const json& animations = ctx.array("animations");
  for (std::size_t a = 0; a < animations.size(); ++a) {
    const json* channels = member(animations[a], "channels");
    if (!channels || !channels->is_array()) continue;
    for (std::size_t c = 0; c < channels->size(); ++c) {
      const json& ch = (*channels)[c];
      const std::string where = element("animations", a) + element(".channels", c);
      const json* target = member(ch, "target");
      const std::string path = target ? string_member(*target, "path") : std::string();
      if (path == "pointer") {
        ctx.warn("KHR_animation_pointer channels are not supported; ignored");
        continue;
      }
      if (path != "translation" && path != "rotation" && path != "scale" && path != "weights") {
        ctx.warn(where + ": unknown target path '" + path + "'; the channel is ignored");
        continue;
      }
      const auto target_node = index_member(*target, "node");
      if (!target_node) continue; // no target node: the channel animates nothing here
      const std::size_t node = checked_index(ctx, static_cast<long long>(*target_node),
                                             ctx.count("nodes"), where, "target node");
      const auto it = index.find(node);
      if (it == index.end()) continue; // not in the scene being loaded
      ctx.use(pointer_of("animations", a) + "/channels/" + std::to_string(c));
      if (path == "weights") {
        read_weight_tracks(ctx, a, ch, it->second, out);
        continue;
      }
      if (out.nodes[it->second].has_matrix)
        ctx.fail(element("nodes", node), "an animated node must not have a matrix (glTF 3.11)");
      Keyframes keys = read_keyframes(ctx, a, ch, animation_path(path));
      if (!keys.times.empty()) out.tracks.push_back({it->second, animation_path(path), keys});
    }
  }
}

std::vector<float> sample_times(const Animation& anim) {
  std::set<float> times;
  for (const Animation::Track& k : anim.tracks)
    times.insert(k.keys.times.begin(), k.keys.times.end());
  const float a = anim.start(), b = anim.end();
  for (int i = 0; i <= kUniformSamples; ++i) times.insert(a + (b - a) * float(i) / kUniformSamples);
  return {times.begin(), times.end()};
}

// Each moving mesh's node-local bounding box placed at every sampled time widens the bounds; a
// transform whose determinant changes sign (a mirroring scale) fails.
void widen_bounds(const Context& ctx, const Animation& anim, const std::vector<glm::dmat4>& rest,
                  const std::vector<std::size_t>& gltf_node, Bounds& bounds) {
  std::vector<Bounds> local(anim.parts.size());
  for (std::size_t i = 0; i < anim.parts.size(); ++i)
    for (const glm::vec3& p : anim.parts[i].positions) local[i].extend(p);
  for (float t : sample_times(anim)) {
    const std::vector<glm::dmat4> world = anim.world_matrices(t);
    for (std::size_t i = 0; i < anim.parts.size(); ++i) {
      const Animation::MeshPart& part = anim.parts[i];
      const Bounds& box = local[i];
      const glm::dmat4& w = world[part.node];
      if (glm::determinant(glm::dmat3(w)) * glm::determinant(glm::dmat3(rest[part.node])) <= 0.0)
        ctx.fail(element("nodes", gltf_node[part.node]),
                 fmt::format("the animation mirrors or collapses the mesh at t = {} s", t));
      for (int c = 0; c < 8; ++c) {
        const glm::dvec3 corner((c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y,
                                (c & 4) ? box.hi.z : box.lo.z);
        bounds.extend(glm::vec3(w * glm::dvec4(corner, 1.0)));
      }
    }
    if (anim.deformed.empty()) continue;
    const std::vector<std::vector<double>> weights = anim.weights(t);
    std::vector<glm::vec3> p, n;
    for (const Animation::DeformedPart& part : anim.deformed) {
      anim.deform(part, world, weights[part.node], p, n);
      for (const glm::vec3& x : p)
        if (std::isfinite(x.x + x.y + x.z)) bounds.extend(x);
    }
  }
}

// The deformed parts whose pose depends on time: a joint moves, or the node's weights are
// animated, or (unskinned) the node moves. Their glTF nodes are mapped to animation nodes;
// joints outside the loaded scene keep their rest matrix (folded into joint_matrix).
void build_deformed(const Context& ctx, const std::vector<char>& dynamic,
                    const std::map<std::size_t, std::uint32_t>& index, ContentNodes& content,
                    const std::vector<char>& weighted, Animation& out) {
  for (Soup::Deform& d : content.deforms) {
    Animation::DeformedPart& part = d.part;
    part.node = index.at(d.gltf_node);
    bool moving = weighted[part.node] || (d.gltf_joints.empty() && dynamic[part.node]);
    for (std::size_t j = 0; j < d.gltf_joints.size(); ++j) {
      const auto it = index.find(d.gltf_joints[j]);
      if (it == index.end()) {
        part.joints.push_back(Animation::kFixedJoint);
        part.joint_matrix[j] = local_world(ctx, d.gltf_joints[j]) * part.joint_matrix[j];
      } else {
        part.joints.push_back(it->second);
        moving = moving || dynamic[it->second];
      }
    }
    if (moving && !part.vertices.empty()) out.deformed.push_back(std::move(part));
  }
}

// The vertices of every moving node's meshes, taken back to the node's frame (tangents by the
// 3x3 block of the rest matrix's inverse, W3^-1, so that W3 t_local = t_world).
void build_parts(const std::vector<char>& dynamic, const std::vector<glm::dmat4>& rest,
                 const std::map<std::size_t, std::uint32_t>& index, const ContentNodes& content,
                 const Scene& scene, Animation& out) {
  std::map<std::uint32_t, Animation::MeshPart> parts;
  std::vector<char> deformed(content.vertex_node.size(), 0); // skinned or morphed: not rigid
  for (const Soup::Deform& d : content.deforms)
    for (std::uint32_t v : d.part.vertices) deformed[v] = 1;
  for (std::size_t v = 0; v < content.vertex_node.size(); ++v) {
    if (deformed[v]) continue;
    const std::uint32_t n = index.at(content.vertex_node[v]);
    if (!dynamic[n]) continue;
    Animation::MeshPart& part = parts[n];
    part.node = n;
    const glm::dmat4 inverse = glm::inverse(rest[n]);
    part.vertices.push_back(std::uint32_t(v));
    part.positions.push_back(glm::vec3(inverse * glm::dvec4(glm::dvec3(scene.positions[v]), 1.0)));
    part.normals.push_back(
        glm::vec3(glm::transpose(glm::dmat3(rest[n])) * glm::dvec3(scene.normals[v])));
    if (!scene.tangents.empty())
      part.tangents.push_back(
          glm::vec3(glm::dmat3(inverse) * glm::dvec3(glm::vec3(scene.tangents[v]))));
  }
  for (auto& [n, part] : parts) out.parts.push_back(std::move(part));
}

} // namespace

std::shared_ptr<const Animation> read_animation(const Context& ctx,
                                                const std::vector<NodeInstance>& instances,
                                                ContentNodes& content, Scene& scene) {
  if (ctx.array("animations").empty()) return nullptr;
  auto anim = std::make_shared<Animation>();
  std::map<std::size_t, std::uint32_t> index; // glTF node -> anim->nodes
  std::vector<std::size_t> gltf_node;
  std::vector<glm::dmat4> rest;
  for (const NodeInstance& inst : instances) {
    index[inst.node] = std::uint32_t(anim->nodes.size());
    gltf_node.push_back(inst.node);
    rest.push_back(inst.world);
    anim->nodes.push_back(node_at_rest(ctx, inst.node));
    if (const auto mesh = index_member(ctx.array("nodes")[inst.node], "mesh");
        mesh && *mesh < ctx.count("meshes"))
      anim->nodes.back().weights = morph_weights(ctx, inst.node, std::size_t(*mesh));
  }
  for (const NodeInstance& inst : instances) { // parents are reached before their children
    const json* children = member(ctx.array("nodes")[inst.node], "children");
    if (!children || !children->is_array()) continue;
    for (const json& child : *children)
      anim->nodes[index.at(std::size_t(as_index(child).value_or(0)))].parent =
          int(index.at(inst.node));
  }
  read_tracks(ctx, index, *anim);
  if (anim->tracks.empty()) return nullptr;
  const std::vector<char> dynamic = anim->dynamic_nodes();
  build_parts(dynamic, rest, index, content, scene, *anim);
  std::vector<char> weighted(anim->nodes.size(), 0);
  for (const Animation::Track& k : anim->tracks)
    if (k.path == Animation::Path::Weights) weighted[k.node] = 1;
  build_deformed(ctx, dynamic, index, content, weighted, *anim);
  for (std::size_t n : content.camera_node) {
    const std::uint32_t i = index.at(n);
    anim->camera_node.push_back(dynamic[i] ? int(i) : -1);
  }
  for (std::size_t n : content.light_node) {
    const std::uint32_t i = index.at(n);
    anim->light_node.push_back(dynamic[i] ? int(i) : -1);
  }
  widen_bounds(ctx, *anim, rest, gltf_node, scene.bounds);
  return anim;
}

} // namespace irad::gltf
