#pragma once
// GLSL 3.30 core sources of the batched VPL passes (raster/passes/batched_passes.h): many VPLs per
// draw call, told apart by gl_InstanceID. Each source is a body: batched_source() puts the version
// line and the array size in front.
#include <string>

namespace irad::gl::shaders {

// Bytes of the shadow uniform block per VPL of a batch (std140): 6 face matrices, 6 rectangles,
// 6 offsets, the position. (The shading's: raster/glsl/deferred_shaders.h.)
inline constexpr int kShadowBytesPerVpl = 6 * 64 + 6 * 16 + 6 * 16 + 16;

// The source with the version line and the arrays sized for `batch` VPLs.
inline std::string batched_source(const char* body, int batch) {
  return "#version 330 core\n#define MAX_BATCH " + std::to_string(batch) + "\n" + body;
}

// Shadow atlas (raster/shadow/shadow_atlas.h): instance i = 6 s + f draws face f of the batch's VPL
// s. The face's clip coordinates give face pixels p = (ndc + 1) R / 2; four clip distances keep p
// inside u_rect[i] (the face's window rectangle that is ever looked up; x0 > x1: not drawn), and
// the atlas pixel is p + u_offset[i]. u_face >= 0 names the instance i instead (the face by face
// draws of the cluster hierarchy, raster/shadow/shadow_lod.h).
inline constexpr const char* batched_shadow_vertex = R"(
layout(location = 0) in vec3 a_position;
#ifdef IRAD_ALPHA
#pragma irad_material_vertex
#endif
layout(std140) uniform ShadowBatch {
  mat4 u_face_vp[6 * MAX_BATCH];
  vec4 u_rect[6 * MAX_BATCH];    // x0, y0, x1, y1 in face pixels
  vec4 u_offset[6 * MAX_BATCH];  // xy: atlas pixel - face pixel
  vec4 u_origin[MAX_BATCH];      // xyz: the VPL's position, w: 1 / far
};
uniform float u_face_size;       // R
uniform vec2 u_atlas_size;       // in pixels
uniform int u_face;              // -1: gl_InstanceID
out vec3 v_position;
flat out vec4 v_origin;
out float gl_ClipDistance[4];
void main() {
  int i = u_face >= 0 ? u_face : gl_InstanceID;
#ifdef IRAD_ALPHA
  copy_material_attributes();
#endif
  v_position = a_position;
  v_origin = u_origin[i / 6];
  vec4 c = u_face_vp[i] * vec4(a_position, 1.0);
  vec2 pw = (c.xy + c.w) * (0.5 * u_face_size); // face pixel times w
  vec4 r = u_rect[i];
  if (r.x > r.z) {
    for (int k = 0; k < 4; ++k) gl_ClipDistance[k] = -1.0;
  } else {
    gl_ClipDistance[0] = pw.x - r.x * c.w;
    gl_ClipDistance[1] = r.z * c.w - pw.x;
    gl_ClipDistance[2] = pw.y - r.y * c.w;
    gl_ClipDistance[3] = r.w * c.w - pw.y;
  }
  c.xy = 2.0 * (pw + u_offset[i].xy * c.w) / u_atlas_size - c.w;
  gl_Position = c;
}
)";

// The distance |p - y| / far as the depth (the depth test keeps the nearest surface: distance
// grows with depth along a ray from y), so the atlas is one depth texture, cleared to 1 (far:
// never shadowed). With alpha, absent fragments (raster/scene/material_glsl.h) are seeded by the
// VPL's position, as ShadowCube's.
inline constexpr const char* batched_shadow_fragment = R"(
in vec3 v_position;
flat in vec4 v_origin;
#ifdef IRAD_ALPHA
#pragma irad_material_fragment
#endif
out vec2 o_gradient; // ShadowAtlas::gradient_texture(): d per face texel, x and y
void main() {
#ifdef IRAD_ALPHA
  if (material_absent(shadow_alpha_key(v_origin.xyz))) discard;
#endif
  float d = length(v_position - v_origin.xyz) * v_origin.w;
  gl_FragDepth = d;
  o_gradient = vec2(dFdx(d), dFdy(d));
}
)";

} // namespace irad::gl::shaders
