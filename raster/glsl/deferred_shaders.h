#pragma once
// GLSL 3.30 core sources of the deferred VPL passes (raster/passes/deferred_shader.h): a batch of
// VPLs shades the camera's G-buffer (raster/image/gbuffer.h) screen-space, one full-screen
// triangle per interleaved set, each fragment summing the VPLs of the draw in a loop. The body
// gets the version line and the array size from batched_source (raster/glsl/batched_shaders.h).
namespace irad::gl::shaders {

// Bytes of the shading block per VPL (std140 BatchVpl below).
inline constexpr int kShadingBytesPerVpl = 9 * 16;

// Tile pixel t of the bound viewport (origin u_tile_origin) stands for image pixel
// k t + (dx, dy) (raster/image/interleaved.h; k = 1, d = 0 without interleaving), whose G-buffer
// texel holds the one surface it sees. Each VPL adds w * C(x) (core/vpl.h) with the maths of
// raster/glsl/shaders.h vpl_fragment; its shadow cube is looked up in the batch's atlas
// (raster/shadow/shadow_atlas.h): GL's cube-map face selection and (s, t) by hand, the texel
// (nearest, clamped to the face's edge, as the cube map's sampler), then the face's place in the
// VPL's blocks: a surface VPL's hemisphere in one block (+z, then the front halves of +x and -x
// side by side, then those of +y and -y one over the other), any other VPL's six faces in two
// blocks of three.
inline constexpr const char* deferred_vpl_fragment = R"(
struct BatchVpl {
  vec4 position;   // xyz
  vec4 normal;     // xyz (spot axis for spots)
  vec4 intensity;  // rgb
  vec4 cone;       // cos inner, cos outer, squared clamp distance, far (the atlas's unit);
                   // directional: texel width, half width (world units)
  ivec4 info;      // kind (0 surface, 1 two-sided, 2 point, 3 spot, 4 directional)
  ivec4 blocks;    // atlas texel of its first block (xy) and of its second (zw); directional:
                   // its tile's first texel (xy)
  vec4 frame[3];   // columns of world -> cube frame; directional: rows of world -> (u, v, depth)
};
layout(std140) uniform VplBatch { BatchVpl u_vpl[MAX_BATCH]; };
uniform sampler2D u_shadow_atlas;
uniform sampler2D u_ortho_atlas;   // orthographic maps (raster/shadow/ortho_atlas.h)
uniform int u_ortho_res;           // M, texels per tile edge
uniform sampler2D u_position;    // G-buffer: xyz, w = 1 on a surface
uniform sampler2D u_normal;      // towards the camera
uniform sampler2D u_albedo;
uniform int u_first;             // the draw's VPLs: u_first .. u_first + u_count - 1
uniform int u_count;
uniform ivec2 u_tile_origin;     // the viewport's lower-left pixel
uniform ivec3 u_pixel;           // k, dx, dy
uniform ivec2 u_size;            // the image
uniform int u_shadow_res;        // R, texels per face edge
uniform int u_shadow_half;       // h = R / 2 + 1 (no integer division per fragment)
uniform float u_min_dist2;       // below this the receiver coincides with the VPL
uniform float u_bias_constant;   // scale-relative
uniform float u_bias_texel;      // angular size of a shadow texel
uniform bool u_apply_albedo;     // false: irradiance / pi only (the resolve multiplies)
out vec4 o_color;
const float INV_PI = 0.31830988618379067;

// Atlas texel minus face texel of face f (+x, -x, +y, -y, +z, -z).
ivec2 face_offset(int kind, ivec4 blocks, int f) {
  int r = u_shadow_res, h = u_shadow_half;
  if (kind == 0) {
    ivec2 o = ivec2(0);                        // +z (and -z, never looked up)
    if (f == 0) o = ivec2(r, 0);
    else if (f == 1) o = ivec2(2 * h, 0);
    else if (f == 2) o = ivec2(r + 2 * h, h - r);
    else if (f == 3) o = ivec2(r + 2 * h, h);
    return blocks.xy + o;
  }
  int g = f < 3 ? f : f - 3;
  return (f < 3 ? blocks.xy : blocks.zw) + ivec2(g * r, 0);
}

// The distance stored in the VPL's cube in direction q (cube frame): the atlas holds it / far.
float stored_distance(int kind, ivec4 blocks, float far, vec3 q) {
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
  return texelFetch(u_shadow_atlas, texel + face_offset(kind, blocks, face), 0).r * far;
}

// A directional VPL's I max(0, n . -d) V / pi (raster/glsl/directional_shaders.h's maths): the
// normal offset by a texel's width times sin theta_x, the map's texel (nearest, clamped to the
// tile), its window depth z_w as the depth (2 z_w - 1) h along d.
vec3 directional_light(int i, vec3 x, vec3 n) {
  vec3 d = u_vpl[i].normal.xyz;
  float cos_x = dot(n, -d);
  if (cos_x <= 0.0) return vec3(0.0);
  vec4 cone = u_vpl[i].cone;
  float sin_x = sqrt(max(1.0 - cos_x * cos_x, 0.0));
  vec4 p = vec4(x + n * (cone.x * sin_x), 1.0);
  vec3 s = vec3(dot(u_vpl[i].frame[0], p), dot(u_vpl[i].frame[1], p), dot(u_vpl[i].frame[2], p));
  ivec2 texel = clamp(ivec2(floor(s.xy * float(u_ortho_res))), ivec2(0), ivec2(u_ortho_res - 1));
  float z = texelFetch(u_ortho_atlas, texel + u_vpl[i].blocks.xy, 0).r;
  if (s.z > (2.0 * z - 1.0) * cone.y + u_bias_constant) return vec3(0.0);
  return u_vpl[i].intensity.rgb * (cos_x * INV_PI);
}

// w * C(x) / rho(x) of VPL i at the surface point x with normal n (0 where it does not reach).
vec3 vpl_light(int i, vec3 x, vec3 n) {
  if (u_vpl[i].info.x == 4) return directional_light(i, x, n);
  vec3 d = x - u_vpl[i].position.xyz;
  float dist2 = dot(d, d);
  if (!(dist2 > u_min_dist2)) return vec3(0.0);
  float dist = sqrt(dist2);
  vec3 w = d / dist;
  float cos_x = dot(n, -w);
  if (cos_x <= 0.0) return vec3(0.0);
  int kind = u_vpl[i].info.x;
  vec4 cone = u_vpl[i].cone;
  float cos_y = dot(u_vpl[i].normal.xyz, w);
  float e = 1.0;
  if (kind == 0) e = max(cos_y, 0.0);
  else if (kind == 1) e = abs(cos_y);
  else if (kind == 3) {
    float t = clamp((cos_y - cone.y) / max(1e-3, cone.x - cone.y), 0.0, 1.0);
    e = t * t;
  }
  if (e <= 0.0) return vec3(0.0);
  // Normal-offset lookup (see vpl_fragment).
  float sin_x = sqrt(max(1.0 - cos_x * cos_x, 0.0));
  vec3 dp = x + n * (dist * u_bias_texel * sin_x) - u_vpl[i].position.xyz;
  mat3 frame = mat3(u_vpl[i].frame[0].xyz, u_vpl[i].frame[1].xyz, u_vpl[i].frame[2].xyz);
  if (length(dp) > stored_distance(kind, u_vpl[i].blocks, cone.w, frame * dp) + u_bias_constant)
    return vec3(0.0);
  float g = e * cos_x / max(dist2, cone.z);
  return u_vpl[i].intensity.rgb * (g * INV_PI);
}

void main() {
  ivec2 p = (ivec2(gl_FragCoord.xy) - u_tile_origin) * u_pixel.x + u_pixel.yz;
  if (p.x >= u_size.x || p.y >= u_size.y) discard;
  vec4 x = texelFetch(u_position, p, 0);
  if (x.w <= 0.0) discard;
  vec3 n = texelFetch(u_normal, p, 0).xyz;
  vec3 sum = vec3(0.0);
  for (int i = u_first; i < u_first + u_count; ++i) sum += vpl_light(i, x.xyz, n);
  if (u_apply_albedo) sum *= texelFetch(u_albedo, p, 0).rgb;
  o_color = vec4(sum, 0.0);
}
)";

} // namespace irad::gl::shaders
