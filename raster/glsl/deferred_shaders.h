#pragma once
// GLSL 3.30 core sources of the deferred VPL passes (raster/passes/deferred_shader.h): a batch of
// VPLs shades the camera's G-buffer (raster/image/gbuffer.h) screen-space, one instanced draw of
// a full-screen triangle per interleaved set, instance i the draw's VPL u_first + i. The VPL's
// record is read per vertex and handed on flat (a record read per fragment is a gather per lane
// on llvmpipe: a loop over the batch's VPLs in one fragment runs at a quarter of the per-VPL
// passes' speed on the Cornell box). The bodies get the version line and the array size from
// batched_source (raster/glsl/batched_shaders.h).
namespace irad::gl::shaders {

// Bytes of the shading block per VPL (std140 BatchVpl below): 4 vec4 more with IRAD_GLOSSY.
inline constexpr int shading_bytes_per_vpl(bool glossy) {
  return (glossy ? 14 : 10) * 16;
}

// The depths of raster/image/receiver_mask.h: a Lambertian receiver's and a glossy one's. The
// deferred triangle lies at window depth u_depth (0.5 unless set), drawn at one of them with
// GL_EQUAL over the mask; both are exact in float, so the test compares equal values.
inline constexpr float kLambertianReceiverDepth = 0.5f;
inline constexpr float kGlossyReceiverDepth = 0.25f;

inline constexpr const char* deferred_vpl_vertex = R"(
struct BatchVpl {
  vec4 position;   // xyz
  vec4 normal;     // xyz (spot axis for spots)
  vec4 intensity;  // rgb
  vec4 cone;       // cos inner, cos outer, squared clamp distance, far (the atlas's unit);
                   // directional: texel width, half width (world units)
  ivec4 info;      // kind (0 surface, 1 two-sided, 2 point, 3 spot, 4 directional), mirror
                   // polygon (-1: not mirrored), its triangles, 1 if a ray can meet its source
                   // (core/lights/vpl.h ray_reachable)
  ivec4 blocks;    // atlas texel of its first block (xy) and of its second (zw); directional:
                   // its tile's first texel (xy)
  vec4 frame[3];   // columns of world -> cube frame; directional: rows of world -> (u, v, depth)
  vec4 mirror;     // a mirrored VPL's plane (n, w), n toward the lit side
#ifdef IRAD_GLOSSY
  vec4 lobe[4];    // a glossy VPL's (core/lights/vpl.h VplLobe): (base, metallic), (f0, f90),
                   // (incident, roughness) (mirrored: reflected), (a(incident), 1); else 0
#endif
};
layout(std140) uniform VplBatch { BatchVpl u_vpl[MAX_BATCH]; };
uniform int u_first;
uniform float u_depth; // window depth (kLambertianReceiverDepth unless set)
#ifdef IRAD_MIRRORS
flat out ivec2 v_mirror;         // polygon, triangles
flat out vec4 v_mirror_plane;
#endif
flat out int v_kind;
flat out ivec4 v_blocks;
flat out vec3 v_vpl_position;
flat out vec3 v_vpl_normal;
flat out vec3 v_vpl_intensity;
flat out vec4 v_cone;
flat out vec4 v_frame[3];
#ifdef IRAD_GLOSSY_RECEIVERS
flat out int v_reachable;
#endif
#ifdef IRAD_GLOSSY_VPLS
flat out vec4 v_lobe[4];
#endif
#ifdef IRAD_RAYS
flat out int v_record; // its layer of the visibility texture
#endif
void main() {
  BatchVpl vpl = u_vpl[u_first + gl_InstanceID];
#ifdef IRAD_RAYS
  v_record = u_first + gl_InstanceID;
#endif
#ifdef IRAD_GLOSSY_RECEIVERS
  v_reachable = vpl.info.w;
#endif
#ifdef IRAD_GLOSSY_VPLS
  v_lobe = vpl.lobe;
#endif
  v_kind = vpl.info.x;
#ifdef IRAD_MIRRORS
  v_mirror = vpl.info.yz;
  v_mirror_plane = vpl.mirror;
#endif
  v_blocks = vpl.blocks;
  v_vpl_position = vpl.position.xyz;
  v_vpl_normal = vpl.normal.xyz;
  v_vpl_intensity = vpl.intensity.rgb;
  v_cone = vpl.cone;
  v_frame = vpl.frame;
  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  gl_Position = vec4(p, 2.0 * u_depth - 1.0, 1.0);
}
)";

// Tile pixel t of the bound viewport (origin u_tile_origin) stands for image pixel
// k t + (dx, dy) (raster/image/interleaved.h; k = 1, d = 0 without interleaving), or for the
// pixel a list names (the edge pixels: raster/image/edge_pixels.h), whose G-buffer
// texel holds the one surface it sees. The instance's VPL adds w * C(x) (core/lights/vpl.h) with
// the maths of raster/glsl/shaders.h vpl_fragment; its shadow cube is looked up in the batch's
// atlas (raster/shadow/shadow_atlas.h): GL's cube-map face selection and (s, t) by hand, the texel
// (nearest, clamped to the face's edge, as the cube map's sampler), then the face's place in the
// VPL's blocks: a surface VPL's hemisphere in one block (+z, then the front halves of +x and -x
// side by side, then those of +y and -y one over the other), any other VPL's six faces in two
// blocks of three. A directional VPL's map is a tile of the orthographic atlas. A mirrored VPL
// (IRAD_MIRRORS) lights only its pyramid: raster/glsl/mirror_shaders.h's test, the polygon's
// corners read from a texture (row p: polygon p, three texels per triangle). In a glossy scene
// (IRAD_GLOSSY: the records carry lobes) the receiver weighs the light by its BRDF where the
// program may meet glossy receivers (IRAD_GLOSSY_RECEIVERS), and a glossy VPL's lobe shape is
// compiled only into the programs that draw glossy VPLs (IRAD_GLOSSY_VPLS): llvmpipe runs both
// sides of every branch under a mask, so code that a draw's pixels never take still costs each
// fragment (raster/image/receiver_mask.h).
inline constexpr const char* deferred_vpl_fragment = R"(
flat in int v_kind;
flat in ivec4 v_blocks;
flat in vec3 v_vpl_position;
flat in vec3 v_vpl_normal;
flat in vec3 v_vpl_intensity;
flat in vec4 v_cone;
flat in vec4 v_frame[3];
uniform sampler2D u_shadow_atlas;    // distance / far
uniform sampler2D u_shadow_gradient; // its gradient per texel (cube_glsl.h)
// const bool u_planes: false without gradients, the centre's distance alone (a constant, so that
// a program without them compiles their fetches away: raster/passes/deferred_shader.h)
#pragma irad_planes
// const bool u_unsure: whether alpha adds the unsure light (vpl_light; a constant, as u_planes;
// its neighbour fetches cost llvmpipe's Cornell box about 10 % of the shading without planes)
#pragma irad_unsure
uniform sampler2D u_ortho_atlas;   // orthographic maps (raster/shadow/ortho_atlas.h)
uniform int u_ortho_res;           // M, texels per tile edge
#ifdef IRAD_RAYS
// Visibility by rays (raster/passes/ray_visibility.h): layer r holds whether uploaded VPL r
// lights tile pixel t's surface (1) or not (0), in place of every shadow lookup.
flat in int v_record;
uniform sampler2DArray u_visibility;
ivec2 g_tile_pixel; // main's t
#endif
uniform sampler2D u_position;    // G-buffer: xyz, w = 1 on a surface
uniform sampler2D u_normal;      // towards the camera
uniform sampler2D u_albedo;      // with IRAD_GLOSSY the directional albedo toward the camera
#ifdef IRAD_GLOSSY_VPLS
flat in vec4 v_lobe[4];
#endif
#ifdef IRAD_GLOSSY_RECEIVERS
flat in int v_reachable;
uniform float u_traced_roughness; // receivers below it: the diffuse lobe from reachable VPLs
uniform sampler2D u_base;        // G-buffer: base, f90
uniform sampler2D u_specular;    // f0, metallic
#endif
#if defined(IRAD_GLOSSY_RECEIVERS) || defined(IRAD_GLOSSY_VPLS)
#pragma irad_brdf
#endif
#ifdef IRAD_GLOSSY_VPLS
#pragma irad_brdf_albedo
#endif
uniform ivec2 u_tile_origin;     // the viewport's lower-left pixel
uniform ivec3 u_pixel;           // k, dx, dy
uniform ivec2 u_size;            // the image
uniform int u_shadow_res;        // R, texels per face edge
uniform int u_shadow_half;       // h = R / 2 + 1 (no integer division per fragment)
uniform float u_min_dist2;       // below this the receiver coincides with the VPL
uniform float u_bias_constant;   // scale-relative
uniform float u_bias_texel;      // angular size of a shadow texel
uniform bool u_apply_albedo;     // false: irradiance / pi only (the resolve multiplies by the
                                 // albedo; glossy: pi f_r / the albedo)
uniform bool u_listed;           // the pixels from a list instead (TilePixels::list):
uniform isampler2D u_pixel_list; // at texel t - u_tile_origin, none where x < 0
out vec4 o_color;
const float INV_PI = 0.31830988618379067;
#pragma irad_luminance

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

#pragma irad_cube_lookup
// Whether the VPL's cube hides the receiver at distance r (bias included) in direction q (cube
// frame; raster/glsl/cube_glsl.h), nq the receiver's normal in that frame: the atlas holds
// distances / far, the gradients beside it. Without them the centre's distance and the receiver's
// plane; with them the occluder's plane and the neighbours' (their distances and gradients:
// cube_glsl.h occluder_distance). With u_unsure, `unsure` tells whether the answer is
// (cube_glsl.h lookup_unsure; false without).
bool shadowed(vec3 q, float r, vec3 nq, out bool unsure) {
  vec2 st;
  int face = cube_face(q, st);
  vec2 at = (st * 0.5 + 0.5) * float(u_shadow_res);
  ivec2 texel = clamp(ivec2(floor(at)), ivec2(0), ivec2(u_shadow_res - 1));
  ivec2 origin = face_offset(face);
  float centre = texelFetch(u_shadow_atlas, texel + origin, 0).r * v_cone.w;
  // The neighbours toward `at`: read by the planes and by the unsure test, else compiled away.
  ivec2 step = toward(at), nx = texel + ivec2(step.x, 0), ny = texel + ivec2(0, step.y);
  bool has_x = nx.x >= 0 && nx.x < u_shadow_res, has_y = ny.y >= 0 && ny.y < u_shadow_res;
  float next_x = -1.0, next_y = -1.0;
  if (u_planes || u_unsure) {
    if (has_x) next_x = texelFetch(u_shadow_atlas, nx + origin, 0).r * v_cone.w;
    if (has_y) next_y = texelFetch(u_shadow_atlas, ny + origin, 0).r * v_cone.w;
  }
  unsure = u_unsure && lookup_unsure(q, nq, r, float(u_shadow_res), centre, next_x, next_y);
  if (!u_planes)
    return r > centre &&
           in_front_of_receiver(q, nq, face, texel, float(u_shadow_res), centre, u_bias_constant);
  vec2 gradient = texelFetch(u_shadow_gradient, texel + origin, 0).rg * v_cone.w;
  vec2 grad_x = has_x ? texelFetch(u_shadow_gradient, nx + origin, 0).rg * v_cone.w : vec2(0.0);
  vec2 grad_y = has_y ? texelFetch(u_shadow_gradient, ny + origin, 0).rg * v_cone.w : vec2(0.0);
  return r > occluder_distance(centre, gradient, at, next_x, grad_x, next_y, grad_y);
}

#ifdef IRAD_MIRRORS
flat in ivec2 v_mirror;
flat in vec4 v_mirror_plane;
uniform sampler2D u_mirror_corners;
#define MIRROR_CORNER(i) texelFetch(u_mirror_corners, ivec2(i, v_mirror.x), 0).xyz
#pragma irad_mirror_pyramid
bool through_mirror(vec3 x) {
  return inside_pyramid(x, v_vpl_position, v_mirror_plane, v_mirror.y);
}
#endif

// A directional VPL's I max(0, n . -d) V / pi (raster/glsl/directional_shaders.h's maths): the
// normal offset by a texel's width times sin theta_x, the map's texel (nearest, clamped to the
// tile), its window depth z_w as the depth (2 z_w - 1) h along d.
vec3 directional_light(vec3 x, vec3 n) {
  float cos_x = dot(n, -v_vpl_normal);
  if (cos_x <= 0.0) return vec3(0.0);
#ifndef IRAD_RAYS // with rays, vpl_light has read V
  float sin_x = sqrt(max(1.0 - cos_x * cos_x, 0.0));
  vec4 p = vec4(x + n * (v_cone.x * sin_x), 1.0);
  vec3 s = vec3(dot(v_frame[0], p), dot(v_frame[1], p), dot(v_frame[2], p));
  ivec2 texel = clamp(ivec2(floor(s.xy * float(u_ortho_res))), ivec2(0), ivec2(u_ortho_res - 1));
  float z = texelFetch(u_ortho_atlas, texel + v_blocks.xy, 0).r;
  if (s.z > (2.0 * z - 1.0) * v_cone.y + u_bias_constant) return vec3(0.0);
#endif
  return v_vpl_intensity * (cos_x * INV_PI);
}

// w * C(x) / rho(x) of the VPL at the surface point x with normal n (0 where it does not reach);
// `unsure` its luminance unshadowed where the shadow lookup was unsure (shadowed()), else 0.
vec3 vpl_light(vec3 x, vec3 n, out float unsure) {
  unsure = 0.0;
#ifdef IRAD_RAYS
  if (texelFetch(u_visibility, ivec3(g_tile_pixel, v_record), 0).r < 0.5) return vec3(0.0);
#endif
  if (v_kind == 4) return directional_light(x, n);
#ifdef IRAD_MIRRORS
  if (v_mirror.x >= 0 && !through_mirror(x)) return vec3(0.0);
#endif
  vec3 d = x - v_vpl_position;
  float dist2 = dot(d, d);
  if (!(dist2 > u_min_dist2)) return vec3(0.0);
  float dist = sqrt(dist2);
  vec3 w = d / dist;
  float cos_x = dot(n, -w);
  if (cos_x <= 0.0) return vec3(0.0);
  float cos_y = dot(v_vpl_normal, w);
  float e = 1.0;
  if (v_kind == 0) e = max(cos_y, 0.0);
  else if (v_kind == 1) e = abs(cos_y);
  else if (v_kind == 3) {
    float t = clamp((cos_y - v_cone.y) / max(1e-3, v_cone.x - v_cone.y), 0.0, 1.0);
    e = t * t;
  }
  if (e <= 0.0) return vec3(0.0);
#ifdef IRAD_RAYS
  bool lookup_unsure = false, hidden = false; // the rays' answer, read above
#else
  // Normal-offset lookup (raster/glsl/cube_glsl.h).
  vec3 dp = lookup_offset(x, n, dist, cos_x, u_bias_texel, v_vpl_position);
  mat3 frame = mat3(v_frame[0].xyz, v_frame[1].xyz, v_frame[2].xyz);
  bool lookup_unsure;
  bool hidden = shadowed(frame * dp, length(dp) - u_bias_constant, frame * n, lookup_unsure);
#endif
  float g = e * cos_x / max(dist2, v_cone.z);
  vec3 light = v_vpl_intensity * (g * INV_PI);
#ifdef IRAD_GLOSSY_VPLS
  if (v_lobe[3].w > 0.0)
    light *= brdf_lobe_shape(v_lobe[0].rgb, v_lobe[0].a, v_lobe[2].w, v_lobe[1].rgb, v_lobe[1].a,
                             v_vpl_normal, v_lobe[2].xyz, w, v_lobe[3].rgb,
                             sqrt(v_cone.z) / dist); // the clamp's sphere
#endif
  if (lookup_unsure) unsure = dot(light, LUMINANCE);
  return hidden ? vec3(0.0) : light;
}

#ifdef IRAD_GLOSSY_RECEIVERS
// What multiplies vpl_light at pixel p (point x, normal n, roughness r) for light arriving from
// unit wi: pi f_r,x(wo, wi) with u_apply_albedo, else that over the G-buffer's albedo (the
// resolve multiplies by it again); a Lambertian pixel's base, or 1, exactly as without
// IRAD_GLOSSY_RECEIVERS.
// Below u_traced_roughness the light of a VPL a ray can meet takes the diffuse lobe alone: the
// glossy camera pass (walk/estimators/glossy_pass.h) adds the specular one.
vec3 receiver_weight(ivec2 p, vec3 x, vec3 n, float r, vec3 wi) {
  vec4 a = texelFetch(u_albedo, p, 0);
  vec3 albedo = a.rgb;
  if (a.w < 0.5) return u_apply_albedo ? albedo : vec3(1.0); // Lambertian: no more fetches
  vec4 b = texelFetch(u_base, p, 0), s = texelFetch(u_specular, p, 0);
  vec3 wo = toward_eye(x);
  vec3 f = brdf_receiver(b.rgb, s.a, r, s.rgb, b.a, brdf_facing_normal(n, wo), wo, wi,
                         v_reachable != 0 && r < u_traced_roughness);
  return u_apply_albedo ? f : brdf_over(f, albedo);
}
#endif

void main() {
  ivec2 t = ivec2(gl_FragCoord.xy) - u_tile_origin;
  ivec2 p = u_listed ? texelFetch(u_pixel_list, t, 0).xy : t * u_pixel.x + u_pixel.yz;
#ifdef IRAD_RAYS
  g_tile_pixel = t;
#endif
  if (p.x < 0 || p.x >= u_size.x || p.y >= u_size.y) discard;
  vec4 x = texelFetch(u_position, p, 0);
  if (x.w <= 0.0) discard;
  float unsure;
  vec4 n = texelFetch(u_normal, p, 0);
  vec3 light = vpl_light(x.xyz, n.xyz, unsure);
  if (light == vec3(0.0) && unsure == 0.0) discard;
#ifdef IRAD_GLOSSY_RECEIVERS
  vec3 wi = v_kind == 4 ? -v_vpl_normal : normalize(v_vpl_position - x.xyz);
  vec3 weight = receiver_weight(p, x.xyz, n.xyz, n.w, wi);
  light *= weight;
  unsure *= dot(weight, LUMINANCE); // the unsure light's scale, per luminance
#else
  if (u_apply_albedo) light *= texelFetch(u_albedo, p, 0).rgb;
#endif
  o_color = vec4(light, unsure);
}
)";

} // namespace irad::gl::shaders
