#pragma once
// The cluster hierarchy of core/mesh/mesh_clusters.h on the GPU, and the choice of what one shadow
// face draws: the nodes whose bounds meet the face's pyramid (clipped to the rectangle the face
// is ever looked up on), and of those the cut with the fewest triangles in which every mesh's
// error is below
//     max(error_per_distance * distance(VPL, node bounds), error_floor)
// (per node: the cheaper of its cheapest acceptable mesh and its children's plans; the original
// triangles are always acceptable).
// With error_per_distance = f * (2 / R), the angle of a texel at a face's centre times a factor
// f, a chosen node's mesh lies within f texels of the original surface as the VPL sees it.
// Culling is exact: a node is left out only when its box lies wholly outside a plane of the
// face's pyramid, where GL would clip all of it. The selected index ranges are drawn with one
// glMultiDrawElements over one index buffer (ranges that touch are merged).
#include "core/mesh/mesh_clusters.h"
#include "raster/context/gl_objects.h"
#include "raster/scene/gpu_scene.h"

#include <glm/glm.hpp>
#include <vector>

namespace irad::gl {

// What one face draws: index ranges of ShadowLod's buffer.
struct ClusterSelection {
  std::vector<GLsizei> counts;
  std::vector<const void*> offsets; // bytes
  std::size_t triangles = 0;
  void clear() {
    counts.clear();
    offsets.clear();
    triangles = 0;
  }
};

// One node's part of a face's cut: indices [first, first + count) of ShadowLod's buffer (its
// mesh, a coarser level or its original triangles), whose triangles lie in the node's bounds.
struct ClusterPick {
  std::uint32_t first = 0, count = 0;
  std::int32_t node = -1;
};

// Appends a pick's range to `out`, merged with the last range when they touch.
void add_pick(const ClusterPick& pick, ClusterSelection& out);

// The four planes a * p + d >= 0 of the pyramid that face pixels p of [x0, x1] x [y0, y1]
// (rect) see through the face view-projection `view_projection` (R texels per edge):
// pixel = (ndc + 1) R / 2, as the batched shadow vertex shader computes it.
std::array<glm::vec4, 4> face_planes(const glm::mat4& view_projection, const glm::vec4& rect,
                                     int resolution);

class ShadowLod {
public:
  // Uploads `clusters` (of gpu's scene) as one index buffer, then frees their indices here (the
  // GPU's copy is the one drawn; at 10M triangles they are half a GiB); `simplify`: whether the
  // inner nodes' meshes may be drawn (false: culling only, the original triangles).
  ShadowLod(const GladGLContext& api, const GpuScene& gpu, MeshClusters clusters, bool simplify);

  // A node's plan for one face (pick()): a range of indices, or its children's plans.
  struct Choice {
    std::uint32_t first = 0, count = 0; // count: the triangles of the plan (0: nothing)
    bool children = false;
  };
  // pick()'s plans, per node: the caller's, so that threads pick at once.
  using Plans = std::vector<Choice>;

  // Appends to `out`, node by node in depth-first order, the cut of the face with pyramid
  // `planes` seen from `origin` (for occlusion culling: raster/shadow/shadow_occlusion.h).
  // error_floor: an error no shadow test can tell (far below the depth bias), so that coplanar
  // simplification, exact up to rounding, serves even a VPL inside a node's bounds.
  void pick(const std::array<glm::vec4, 4>& planes, const glm::vec3& origin,
            float error_per_distance, float error_floor, Plans& plans,
            std::vector<ClusterPick>& out) const;
  // A vertex array of the current context over the scene's vertices and this hierarchy's
  // indices (vertex arrays are not shared between contexts): what draw() draws through.
  VertexArray vertex_array() const { return gpu_->vertex_array_with(indices_); }
  // Draws `selection` through `vao` (the bound program's state is the caller's).
  void draw(const ClusterSelection& selection, const VertexArray& vao) const;

  // Every triangle of the scene that is not in the hierarchy (Mask and Blend materials) has to be
  // drawn by the caller. Its indices are empty (on the GPU only).
  const MeshClusters& clusters() const { return clusters_; }
  std::size_t gpu_bytes() const { return index_count_ * sizeof(std::uint32_t); }

private:
  struct Query {
    const std::array<glm::vec4, 4>* planes;
    glm::vec3 origin;
    float error_per_distance, error_floor;
    Plans* plans;
  };
  // A node's acceptable mesh of at most this many triangles is taken without a look below.
  static constexpr std::uint32_t kSmallEnough = 64;
  std::uint32_t plan(std::int32_t id, const Query& q) const;
  void emit_plan(std::int32_t id, const Plans& plans, std::vector<ClusterPick>& out) const;

  const GladGLContext* api_;
  const GpuScene* gpu_;
  MeshClusters clusters_;
  std::size_t index_count_ = 0; // of the uploaded indices
  bool simplify_;
  Buffer indices_;
};

} // namespace irad::gl
