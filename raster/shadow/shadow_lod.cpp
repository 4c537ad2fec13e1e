#include "raster/shadow/shadow_lod.h"

#include <algorithm>
#include <cmath>

namespace irad::gl {

namespace {

// The largest and smallest of a * p + d over the box b.
glm::vec2 plane_range(const glm::vec4& plane, const Bounds& b) {
  const glm::vec3 a(plane);
  const glm::vec3 centre = b.center(), half = 0.5f * (b.hi - b.lo);
  const float mid = glm::dot(a, centre) + plane.w;
  const float reach = glm::dot(glm::abs(a), half);
  return {mid - reach, mid + reach};
}

} // namespace

void add_pick(const ClusterPick& pick, ClusterSelection& out) {
  if (pick.count == 0) return;
  // Byte offsets into the index buffer, as glMultiDrawElements takes them (pointers that are no
  // address: their arithmetic is done on integers).
  const std::uintptr_t offset = std::uintptr_t(pick.first) * sizeof(std::uint32_t);
  out.triangles += pick.count / 3;
  const auto end_of_last = [&] {
    return reinterpret_cast<std::uintptr_t>(out.offsets.back()) +
           std::uintptr_t(out.counts.back()) * sizeof(std::uint32_t);
  };
  if (!out.counts.empty() && end_of_last() == offset) {
    out.counts.back() += static_cast<GLsizei>(pick.count);
    return;
  }
  out.counts.push_back(static_cast<GLsizei>(pick.count));
  out.offsets.push_back(reinterpret_cast<const void*>(offset));
}

std::array<glm::vec4, 4> face_planes(const glm::mat4& view_projection, const glm::vec4& rect,
                                     int resolution) {
  // Clip c = M p (rows of M), face pixel times w: pw = (c.xy + c.w) R / 2; inside where
  // x0 w <= pw.x <= x1 w and y0 w <= pw.y <= y1 w (w = c.w > 0 in front of the VPL).
  const glm::mat4 t = glm::transpose(view_projection); // t[i]: row i of M
  const float h = 0.5f * static_cast<float>(resolution);
  const glm::vec4 px = h * (t[0] + t[3]), py = h * (t[1] + t[3]), w = t[3];
  return {px - rect.x * w, rect.z * w - px, py - rect.y * w, rect.w * w - py};
}

ShadowLod::ShadowLod(const GladGLContext& api, const GpuScene& gpu, MeshClusters clusters,
                     bool simplify)
    : api_(&api), gpu_(&gpu), clusters_(std::move(clusters)), simplify_(simplify),
      indices_(make_buffer(api)) {
  index_count_ = clusters_.index_count();
  const auto bytes = static_cast<GLsizeiptr>(index_count_ * sizeof(std::uint32_t));
  api.BindBuffer(GL_ARRAY_BUFFER, indices_.get()); // not the bound VAO's element buffer
  if (!clusters_.stored_indices) {
    api.BufferData(GL_ARRAY_BUFFER, bytes, clusters_.indices.data(), GL_STATIC_DRAW);
  } else { // straight from the cache file into the buffer's storage (a throw deletes it)
    const StoredIndices& stored = *clusters_.stored_indices;
    fill_buffer(
        api, GL_ARRAY_BUFFER, static_cast<std::size_t>(bytes), GL_STATIC_DRAW,
        [&](void* storage) { stored.copy_to(static_cast<std::uint32_t*>(storage)); },
        "shadow hierarchy");
  }
  api.BindBuffer(GL_ARRAY_BUFFER, 0);
  std::vector<std::uint32_t>().swap(clusters_.indices);
  clusters_.stored_indices.reset(); // closes the cache file
}

// Per node visited: what it draws (a mesh range, its children, or nothing) and how many
// triangles that is; the cheapest of its acceptable meshes and its children's plans.
std::uint32_t ShadowLod::plan(std::int32_t id, const Query& q) const {
  const ClusterNode& node = clusters_.nodes[static_cast<std::size_t>(id)];
  Choice& c = (*q.plans)[static_cast<std::size_t>(id)];
  bool inside = true, outside = false;
  for (const glm::vec4& p : *q.planes) {
    const glm::vec2 r = plane_range(p, node.bounds);
    // A margin of float rounding (relative to the terms): culling only what is surely out.
    const float margin =
        1e-5f * (std::abs(p.w) + glm::dot(glm::abs(glm::vec3(p)),
                                          glm::abs(node.bounds.hi) + glm::abs(node.bounds.lo)));
    if (r.y < -margin) outside = true;
    if (r.x < margin) inside = false;
  }
  c = {0, 0, false};
  if (outside) return 0;
  // The original triangles below: always right.
  c.first = node.leaf_first;
  c.count = node.leaf_count;
  if (!simplify_) {
    if (node.leaf() || inside) return c.count;
  } else {
    const float allowed =
        std::max(q.error_floor, q.error_per_distance * distance_to(node.bounds, q.origin));
    if (node.error <= allowed && node.mesh_count < c.count) {
      c.first = node.mesh_first;
      c.count = node.mesh_count;
    }
    for (std::uint32_t l = 0; l < node.levels_count; ++l) {
      const ClusterLevel& level = clusters_.levels[node.levels_first + l];
      if (level.error <= allowed && level.count < c.count) {
        c.first = level.first;
        c.count = level.count;
      }
    }
    // A leaf, or a mesh too small for its children to do much better.
    if (node.leaf() || c.count <= 3 * kSmallEnough) return c.count;
  }
  // (c stays valid: the plans are not resized while planning.)
  const std::uint32_t below = plan(node.children[0], q) + plan(node.children[1], q);
  if (below < c.count) {
    c.children = true;
    c.count = below;
  }
  return c.count;
}

void ShadowLod::emit_plan(std::int32_t id, const Plans& plans,
                          std::vector<ClusterPick>& out) const {
  const Choice& c = plans[static_cast<std::size_t>(id)];
  if (c.count == 0) return;
  const ClusterNode& node = clusters_.nodes[static_cast<std::size_t>(id)];
  if (!c.children) {
    out.push_back({c.first, c.count, id});
    return;
  }
  emit_plan(node.children[0], plans, out);
  emit_plan(node.children[1], plans, out);
}

void ShadowLod::pick(const std::array<glm::vec4, 4>& planes, const glm::vec3& origin,
                     float error_per_distance, float error_floor, Plans& plans,
                     std::vector<ClusterPick>& out) const {
  plans.resize(clusters_.nodes.size());
  const Query q{&planes, origin, error_per_distance, error_floor, &plans};
  for (std::int32_t root : clusters_.roots) {
    plan(root, q);
    emit_plan(root, plans, out);
  }
}

void ShadowLod::draw(const ClusterSelection& selection, const VertexArray& vao) const {
  if (selection.counts.empty()) return;
  api_->BindVertexArray(vao.get());
  api_->MultiDrawElements(GL_TRIANGLES, selection.counts.data(), GL_UNSIGNED_INT,
                          selection.offsets.data(), static_cast<GLsizei>(selection.counts.size()));
}

} // namespace irad::gl
