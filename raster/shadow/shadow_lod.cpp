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
    : api_(&api), clusters_(std::move(clusters)), simplify_(simplify), indices_(make_buffer(api)) {
  api.BindBuffer(GL_ARRAY_BUFFER, indices_.get()); // not the bound VAO's element buffer
  api.BufferData(GL_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(clusters_.indices.size() * sizeof(std::uint32_t)),
                 clusters_.indices.data(), GL_STATIC_DRAW);
  api.BindBuffer(GL_ARRAY_BUFFER, 0);
  vao_ = gpu.vertex_array_with(indices_);
}

void ShadowLod::emit(std::uint32_t first, std::uint32_t count, ClusterSelection& out) const {
  if (count == 0) return;
  const auto* offset = reinterpret_cast<const char*>(std::uintptr_t(first) * sizeof(std::uint32_t));
  out.triangles += count / 3;
  if (!out.counts.empty() &&
      static_cast<const char*>(out.offsets.back()) + out.counts.back() * sizeof(std::uint32_t) ==
          offset) {
    out.counts.back() += static_cast<GLsizei>(count);
    return;
  }
  out.counts.push_back(static_cast<GLsizei>(count));
  out.offsets.push_back(offset);
}

void ShadowLod::select(const std::array<glm::vec4, 4>& planes, const glm::vec3& origin,
                       float error_per_distance, float error_floor, ClusterSelection& out) const {
  const std::vector<ClusterNode>& nodes = clusters_.nodes;
  stack_.assign(clusters_.roots.rbegin(), clusters_.roots.rend());
  while (!stack_.empty()) {
    const ClusterNode& node = nodes[static_cast<std::size_t>(stack_.back())];
    stack_.pop_back();
    bool inside = true, outside = false;
    for (const glm::vec4& p : planes) {
      const glm::vec2 r = plane_range(p, node.bounds);
      // A margin of float rounding (relative to the terms): culling only what is surely out.
      const float margin =
          1e-5f * (std::abs(p.w) + glm::dot(glm::abs(glm::vec3(p)),
                                            glm::abs(node.bounds.hi) + glm::abs(node.bounds.lo)));
      if (r.y < -margin) outside = true;
      if (r.x < margin) inside = false;
    }
    if (outside) continue;
    const float allowed =
        std::max(error_floor, error_per_distance * distance_to(node.bounds, origin));
    // The acceptable mesh of the node with the fewest triangles: its own or a coarser level.
    std::uint32_t first = 0, count = ~0u;
    if (simplify_ && node.error <= allowed) {
      first = node.mesh_first;
      count = node.mesh_count;
    }
    for (std::uint32_t l = 0; simplify_ && l < node.levels_count; ++l) {
      const ClusterLevel& level = clusters_.levels[node.levels_first + l];
      if (level.error <= allowed && level.count < count) {
        first = level.first;
        count = level.count;
      }
    }
    if (count != ~0u) {
      emit(first, count, out);
    } else if (node.leaf() || (inside && !simplify_)) {
      emit(node.leaf_first, node.leaf_count, out); // the original triangles below
    } else {
      stack_.push_back(node.children[1]); // the first child first: leaves in order, merged
      stack_.push_back(node.children[0]);
    }
  }
}

void ShadowLod::draw(const ClusterSelection& selection) const {
  if (selection.counts.empty()) return;
  api_->BindVertexArray(vao_.get());
  api_->MultiDrawElements(GL_TRIANGLES, selection.counts.data(), GL_UNSIGNED_INT,
                          selection.offsets.data(), static_cast<GLsizei>(selection.counts.size()));
}

} // namespace irad::gl
