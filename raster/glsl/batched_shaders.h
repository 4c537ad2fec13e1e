#pragma once
// GLSL 3.30 core sources of the batched VPL passes (raster/passes/batched_passes.h): many VPLs per draw
// call, told apart by gl_InstanceID. Each source is a body: batched_source() puts the version
// line and the array size in front.
#include <string>

namespace irad::gl::shaders {

// Bytes of the uniform blocks per VPL of a batch (std140): shadow data (6 face matrices, 6
// rectangles, 6 offsets, the position) and shading data (BatchVpl).
inline constexpr int kShadowBytesPerVpl = 6 * 64 + 6 * 16 + 6 * 16 + 16;
inline constexpr int kShadingBytesPerVpl = 9 * 16;

// The source with the version line and the arrays sized for `batch` VPLs.
inline std::string batched_source(const char* body, int batch) {
  return "#version 330 core\n#define MAX_BATCH " + std::to_string(batch) + "\n" + body;
}

// Shadow atlas (raster/shadow/shadow_atlas.h): instance i = 6 s + f draws face f of the batch's VPL s.
// The face's clip coordinates give face pixels p = (ndc + 1) R / 2; four clip distances keep
// p inside u_rect[i] (the face's window rectangle that is ever looked up; x0 > x1: not drawn),
// and the atlas pixel is p + u_offset[i]. u_face >= 0 names the instance i instead (the face by
// face draws of the cluster hierarchy, raster/shadow/shadow_lod.h).
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
// never shadowed). With alpha, absent fragments (raster/scene/material_glsl.h) are seeded by the VPL's
// position, as ShadowCube's.
inline constexpr const char* batched_shadow_fragment = R"(
in vec3 v_position;
flat in vec4 v_origin;
#ifdef IRAD_ALPHA
#pragma irad_material_fragment
#endif
void main() {
#ifdef IRAD_ALPHA
  if (material_absent(shadow_alpha_key(v_origin.xyz))) discard;
#endif
  gl_FragDepth = length(v_position - v_origin.xyz) * v_origin.w;
}
)";

// Shading: instance i is the batch's VPL u_first + i. The draw's view-projection is the one the
// per-VPL pass of the same set uses (the VPLs of a batch are drawn set by set, each set into its
// tile through the viewport), and the vertex maths is camera_vertex's, so the depth pre-pass
// (CameraPasses) holds exactly the visible surface for GL_LEQUAL. The VPL's data is read here,
// once per vertex, and handed on flat.
inline constexpr const char* batched_vpl_vertex = R"(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
#pragma irad_material_vertex
struct BatchVpl {
  vec4 position;   // xyz
  vec4 normal;     // xyz (spot axis for spots)
  vec4 intensity;  // rgb
  vec4 cone;       // cos inner, cos outer, squared clamp distance, far (the atlas's unit)
  ivec4 info;      // kind (0 surface, 1 two-sided, 2 point, 3 spot)
  ivec4 blocks;    // atlas texel of its first block (xy) and of its second (zw)
  vec4 frame[3];   // columns of world -> cube frame
};
layout(std140) uniform VplBatch { BatchVpl u_vpl[MAX_BATCH]; };
uniform mat4 u_view_projection;
uniform int u_first;
out vec3 v_position;
out vec3 v_normal;
flat out int v_kind;
flat out ivec4 v_blocks;
flat out vec3 v_vpl_position;
flat out vec3 v_vpl_normal;
flat out vec3 v_vpl_intensity;
flat out vec4 v_cone;
flat out mat3 v_frame;
invariant gl_Position;
void main() {
  v_position = a_position;
  v_normal = a_normal;
  copy_material_attributes();
  BatchVpl vpl = u_vpl[u_first + gl_InstanceID];
  v_kind = vpl.info.x;
  v_blocks = vpl.blocks;
  v_vpl_position = vpl.position.xyz;
  v_vpl_normal = vpl.normal.xyz;
  v_vpl_intensity = vpl.intensity.rgb;
  v_cone = vpl.cone;
  v_frame = mat3(vpl.frame[0].xyz, vpl.frame[1].xyz, vpl.frame[2].xyz);
  gl_Position = u_view_projection * vec4(a_position, 1.0);
}
)";

// One VPL's contribution w * C(x) (core/vpl.h), as raster/glsl/shaders.h vpl_fragment, with the shadow
// cube looked up in the atlas: GL's cube-map face selection and (s, t) by hand, the texel
// (nearest, clamped to the face's edge, as the cube map's sampler), then the face's place in the
// VPL's blocks (raster/shadow/shadow_atlas.h): a surface VPL's hemisphere in one block (+z, then the
// front halves of +x and -x side by side, then those of +y and -y one over the other), any other
// VPL's six faces in two blocks of three.
inline constexpr const char* batched_vpl_fragment = R"(
in vec3 v_position;
in vec3 v_normal;
#pragma irad_material_fragment
flat in int v_kind;
flat in ivec4 v_blocks;
flat in vec3 v_vpl_position;
flat in vec3 v_vpl_normal;
flat in vec3 v_vpl_intensity;
flat in vec4 v_cone;
flat in mat3 v_frame;
uniform sampler2D u_shadow_atlas;
uniform int u_shadow_res;        // R, texels per face edge
uniform int u_shadow_half;       // h = R / 2 + 1 (no integer division per fragment)
uniform float u_min_dist2;       // below this the receiver coincides with the VPL
uniform float u_bias_constant;   // scale-relative
uniform float u_bias_texel;      // angular size of a shadow texel
uniform bool u_apply_albedo;
out vec4 o_color;
const float INV_PI = 0.31830988618379067;

// Atlas texel minus face texel of face f (+x, -x, +y, -y, +z, -z).
ivec2 face_offset(int f) {
  int r = u_shadow_res, h = u_shadow_half;
  if (v_kind == 0) {
    ivec2 o = ivec2(0);                        // +z (and -z, never looked up)
    if (f == 0) o = ivec2(r, 0);
    else if (f == 1) o = ivec2(2 * h, 0);
    else if (f == 2) o = ivec2(r + 2 * h, h - r);
    else if (f == 3) o = ivec2(r + 2 * h, h);
    return v_blocks.xy + o;
  }
  int g = f < 3 ? f : f - 3;
  return (f < 3 ? v_blocks.xy : v_blocks.zw) + ivec2(g * r, 0);
}

// The distance stored in the VPL's cube in direction q (cube frame): the atlas holds it / far.
float stored_distance(vec3 q) {
  vec3 a = abs(q);
  int face;
  vec2 st;
  if (a.x >= a.y && a.x >= a.z) {
    face = q.x > 0.0 ? 0 : 1;
    st = vec2(q.x > 0.0 ? -q.z : q.z, -q.y) / a.x;
  } else if (a.y >= a.z) {
    face = q.y > 0.0 ? 2 : 3;
    st = vec2(q.x, q.y > 0.0 ? q.z : -q.z) / a.y;
  } else {
    face = q.z > 0.0 ? 4 : 5;
    st = vec2(q.z > 0.0 ? q.x : -q.x, -q.y) / a.z;
  }
  ivec2 texel = clamp(ivec2(floor((st * 0.5 + 0.5) * float(u_shadow_res))), ivec2(0),
                      ivec2(u_shadow_res - 1));
  return texelFetch(u_shadow_atlas, texel + face_offset(face), 0).r * v_cone.w;
}

void main() {
#ifdef IRAD_ALPHA
  if (material_absent(camera_alpha_key())) discard;
#endif
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 d = v_position - v_vpl_position;
  float dist2 = dot(d, d);
  if (!(dist2 > u_min_dist2)) discard;
  float dist = sqrt(dist2);
  vec3 w = d / dist;
  float cos_x = dot(n, -w);
  if (cos_x <= 0.0) discard;
  float cos_y = dot(v_vpl_normal, w);
  float e = 1.0;
  if (v_kind == 0) e = max(cos_y, 0.0);
  else if (v_kind == 1) e = abs(cos_y);
  else if (v_kind == 3) {
    float t = clamp((cos_y - v_cone.y) / max(1e-3, v_cone.x - v_cone.y), 0.0, 1.0);
    e = t * t;
  }
  if (e <= 0.0) discard;
  // Normal-offset lookup (see vpl_fragment).
  float sin_x = sqrt(max(1.0 - cos_x * cos_x, 0.0));
  vec3 dp = v_position + n * (dist * u_bias_texel * sin_x) - v_vpl_position;
  if (length(dp) > stored_distance(v_frame * dp) + u_bias_constant) discard;
  vec3 albedo = u_apply_albedo ? material_albedo() : vec3(1.0);
  float g = e * cos_x / max(dist2, v_cone.z);
  o_color = vec4(v_vpl_intensity * (g * INV_PI) * albedo, 0.0);
}
)";

} // namespace irad::gl::shaders
