#pragma once
// GLSL 3.30 core sources of the batched VPL passes (raster/passes/batched_passes.h): many VPLs per
// draw call, told apart by gl_InstanceID. Each source is a body: batched_source() puts the version
// line and the array size in front.
#include <string>

namespace irad::gl::shaders {

// Bytes of the shadow uniform block per VPL of a batch (std140): 6 face matrices, 6 rectangles,
// 6 offsets, the position, the mirror plane. (The shading's: raster/glsl/deferred_shaders.h.)
inline constexpr int kShadowBytesPerVpl = 6 * 64 + 6 * 16 + 6 * 16 + 16 + 16;

// The source with the version line and the arrays sized for `batch` VPLs (and `defines`, lines
// of #define, after them).
inline std::string batched_source(const char* body, int batch, const std::string& defines = "") {
  return "#version 330 core\n#define MAX_BATCH " + std::to_string(batch) + "\n" + defines + body;
}

// Shadow atlas (raster/shadow/shadow_atlas.h): instance i = 6 s + f draws face f of the batch's VPL
// s. The face's clip coordinates give face pixels p = (ndc + 1) R / 2; four clip distances keep p
// inside u_rect[i] (the face's window rectangle that is ever looked up; x0 > x1: not drawn), and
// the atlas pixel is p + u_offset[i]. u_face >= 0 names the instance i instead (the face by face
// draws of the cluster hierarchy, raster/shadow/shadow_lod.h).
// With mirrors in the scene (IRAD_MIRRORS, material_source) a batch may hold mirrored VPLs
// (core/scene/mirrors.h), whose cube is ShadowCube's unfolded one (raster/glsl/mirror_shaders.h):
// the real scene and the scene reflected in the mirror plane, both clipped to the lit side of the
// plane. Such a batch is drawn with u_copies = 2: instance 2 i + c draws copy c of face i (c = 1
// the reflected scene; nothing for a VPL that is not mirrored, u_mirror[s] = 0).
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
  vec4 u_mirror[MAX_BATCH];      // a mirrored VPL's plane (n, w), n toward the lit side; else 0
};
uniform float u_face_size;       // R
uniform vec2 u_atlas_size;       // in pixels
uniform int u_face;              // -1: gl_InstanceID
out vec3 v_position;
flat out vec4 v_origin;
#ifdef IRAD_MIRRORS
uniform int u_copies;            // 1, or 2 for a batch with mirrored VPLs
uniform float u_mirror_clip;     // the clip plane lies this far on the lit side of the mirror
out float gl_ClipDistance[5];
#else
out float gl_ClipDistance[4];
#endif
void main() {
#ifdef IRAD_MIRRORS
  int copy = u_face >= 0 ? 0 : gl_InstanceID % u_copies;
  int i = u_face >= 0 ? u_face : gl_InstanceID / u_copies;
  vec4 m = u_mirror[i / 6];
  vec3 p = a_position;
  if (m.xyz == vec3(0.0)) {
    gl_ClipDistance[4] = copy == 0 ? 1.0 : -1.0;
  } else {
    gl_ClipDistance[4] = dot(m.xyz, a_position) + m.w - u_mirror_clip;
    if (copy == 1) p -= 2.0 * (dot(m.xyz, p) + m.w) * m.xyz;
  }
#else
  int i = u_face >= 0 ? u_face : gl_InstanceID;
  vec3 p = a_position;
#endif
#ifdef IRAD_ALPHA
  copy_material_attributes();
#endif
  v_position = p;
  v_origin = u_origin[i / 6];
  vec4 c = u_face_vp[i] * vec4(p, 1.0);
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
