#pragma once
// Occlusion culling of a shadow face's clusters against what the face already holds, exact: a
// cluster is left out only when no fragment of it could pass the depth test.
//
// A face of the batched atlas (raster/shadow/shadow_atlas.h) stores per texel t the nearest
// distance d_t = |p - y| / far of what was drawn into it (gl_FragDepth of the interpolated point
// p on the ray through the texel's centre). A cluster's triangles lie in its node's box B; a
// fragment of them at texel t lies in B on that ray, so its distance is at least
//     max(dist(y, B), z_min(B) / cos(theta_t)),
// z_min(B) the box's least depth along the face's axis (its corners' clip w) and theta_t the
// angle of t's ray from the axis. If at every texel the box's projection covers this bound
// exceeds d_t (equivalently: dist(y, B) > d_t, or z_min(B) > z_t = d_t cos(theta_t), the stored
// point's own depth along the axis), the depth test (GL_LESS) rejects every fragment the
// cluster has: drawing it changes nothing. The axial bound is what hides a room behind a wall
// seen at an angle; the distance bound serves boxes off the axis.
//
// FaceDepthBound keeps the largest d_t and z_t per tile of kTile x kTile texels of a face (a
// bound over the texels a box covers), from the atlas's depth read back after the clusters
// nearest the VPL were drawn (ShadowAtlas: the occluders that hide most of a room's or a
// corridor's far side). Faces are 90-degree square frusta (raster/shadow/shadow_cube.h).
#include "core/scene/bounds.h"

#include <glm/glm.hpp>
#include <vector>

namespace irad::gl {

class FaceDepthBound {
public:
  static constexpr int kTile = 8;

  // depth: the atlas's depth texels, row-major from the bottom row, atlas_size.x per row; the
  // face's texel (i, j) is atlas texel offset + (i, j); rect: the face pixels ever drawn (x0, y0,
  // x1, y1) of the face's R x R (`resolution`) texels.
  FaceDepthBound(const float* depth, glm::ivec2 atlas_size, glm::ivec2 offset, glm::ivec4 rect,
                 int resolution);

  // False only when no fragment of a triangle inside `box` could be stored nearer than what the
  // face holds: seen through the face's view-projection `view_projection` from `origin`, with
  // 1 / far `inv_far` and R = `resolution` (face pixel = (ndc + 1) R / 2).
  bool may_show(const Bounds& box, const glm::mat4& view_projection, int resolution,
                const glm::vec3& origin, float inv_far) const;

private:
  glm::ivec4 rect_;
  glm::ivec2 tiles_;
  std::vector<float> max_distance_, max_axial_; // per tile, row-major: d_t, z_t / far
};

} // namespace irad::gl
