#pragma once
// GLSL 3.30 core sources of the raster's passes.
namespace irad::gl::shaders {

// Camera passes share one vertex shader; `invariant` makes the depth pre-pass and the shading
// passes produce bit-identical depths, so GL_LEQUAL selects exactly the visible surface.
inline constexpr const char* camera_vertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in ivec2 a_normal; // octahedral (raster/scene/octahedral.h)
#pragma irad_material_vertex
uniform mat4 u_view_projection;
out vec3 v_position;
out vec3 v_normal;
invariant gl_Position;
// octahedral_decode of raster/scene/octahedral.cpp.
vec3 octahedral_decode(ivec2 e) {
  vec2 p = max(vec2(e) / 32767.0, vec2(-1.0));
  vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
  if (n.z < 0.0)
    n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return normalize(n);
}
void main() {
  v_position = a_position;
  v_normal = octahedral_decode(a_normal);
  copy_material_attributes();
  gl_Position = u_view_projection * vec4(a_position, 1.0);
}
)";

// With alpha (raster/scene/material_glsl.h), absent fragments leave the depth of what lies behind.
inline constexpr const char* depth_fragment = R"(#version 330 core
#ifdef IRAD_ALPHA
in vec3 v_position;
#pragma irad_material_fragment
#endif
void main() {
#ifdef IRAD_ALPHA
  if (material_absent(camera_alpha_key())) discard;
#endif
}
)";

// Visible emitters: L_e(x), front face only unless double-sided.
inline constexpr const char* emission_fragment = R"(#version 330 core
in vec3 v_position;
in vec3 v_normal;
#pragma irad_material_fragment
uniform bool u_double_sided;
out vec4 o_color;
void main() {
  if (!u_double_sided && !gl_FrontFacing) discard;
#ifdef IRAD_ALPHA
  if (material_absent(camera_alpha_key())) discard;
#endif
  o_color = vec4(material_emission(), 0.0);
}
)";

// One VPL's contribution w * C(x) (core/lights/vpl.h), added by blending.
inline constexpr const char* vpl_fragment = R"(#version 330 core
in vec3 v_position;
in vec3 v_normal;
#pragma irad_material_fragment
uniform vec3 u_vpl_position;
uniform vec3 u_vpl_normal;
uniform vec3 u_vpl_intensity;
uniform int u_vpl_kind;          // 0 surface, 1 two-sided, 2 point, 3 spot
uniform vec2 u_spot_cos;         // cos inner, cos outer
uniform float u_dmin2;           // squared clamp distance (0 for punctual lights)
uniform float u_min_dist2;       // below this the receiver coincides with the VPL
uniform samplerCube u_shadow;
uniform mat3 u_shadow_frame;     // world -> the cube's frame
uniform float u_bias_constant;   // scale-relative
uniform float u_bias_texel;      // angular size of a shadow texel
uniform bool u_planes;           // the occluder planes' test (else the receiver's plane)
uniform bool u_apply_albedo;     // false: irradiance / pi only (interleaved mode multiplies later)
#ifdef IRAD_GLOSSY
// The glTF BRDF at both ends (raster/glsl/deferred_shaders.h's maths): the VPL's lobe as
// BatchVpl's lobe[4] (w of [3]: 1 for a glossy VPL), the receiver's material from its uniforms.
uniform vec4 u_lobe[4];
uniform bool u_vpl_reachable;     // a ray can meet its source (core/lights/vpl.h ray_reachable)
uniform float u_traced_roughness; // receivers below it: the diffuse lobe from reachable VPLs
#pragma irad_brdf
#pragma irad_brdf_albedo
#endif
out vec4 o_color;
const float INV_PI = 0.31830988618379067;
#pragma irad_cube_lookup
// Whether the cube hides the receiver at distance r (bias included) in direction q (cube frame),
// nq the receiver's normal in that frame: it holds (distance, gradient) per texel
// (raster/glsl/cube_glsl.h); R = 2 / u_bias_texel texels per face edge. Without the occluder
// planes (u_planes false: the batched passes' test) the centre's distance and the receiver's
// plane; with them the neighbours only where the plane alone would shadow.
bool shadowed(vec3 q, float r, vec3 nq) {
  vec3 s = texture(u_shadow, q).rgb;
  vec2 st;
  int face = cube_face(q, st);
  float res = 2.0 / u_bias_texel;
  vec2 at = (st * 0.5 + 0.5) * res;
  vec2 texel = clamp(floor(at), vec2(0.0), vec2(res - 1.0));
  if (!u_planes)
    return r > s.r && in_front_of_receiver(q, nq, face, ivec2(texel), res, s.r, u_bias_constant);
  vec2 step = vec2(toward(at));
  vec2 nx = texel + vec2(step.x, 0.0), ny = texel + vec2(0.0, step.y);
  vec3 sx = nx.x >= 0.0 && nx.x < res
                ? texture(u_shadow, face_direction(face, (nx + 0.5) / res * 2.0 - 1.0)).rgb
                : vec3(-1.0, 0.0, 0.0);
  vec3 sy = ny.y >= 0.0 && ny.y < res
                ? texture(u_shadow, face_direction(face, (ny + 0.5) / res * 2.0 - 1.0)).rgb
                : vec3(-1.0, 0.0, 0.0);
  return r > occluder_distance(s.r, s.gb, at, sx.r, sx.gb, sy.r, sy.gb);
}
void main() {
#ifdef IRAD_ALPHA
  if (material_absent(camera_alpha_key())) discard;
#endif
  vec3 n = material_normal(normalize(v_normal));
  if (!gl_FrontFacing) n = -n;
  vec3 d = v_position - u_vpl_position;
  float dist2 = dot(d, d);
  if (!(dist2 > u_min_dist2)) discard;
  float dist = sqrt(dist2);
  vec3 w = d / dist;
  float cos_x = dot(n, -w);
  if (cos_x <= 0.0) discard;
  float cos_y = dot(u_vpl_normal, w);
  float e = 1.0;
  if (u_vpl_kind == 0) e = max(cos_y, 0.0);
  else if (u_vpl_kind == 1) e = abs(cos_y);
  else if (u_vpl_kind == 3) {
    float t = clamp((cos_y - u_spot_cos.y) / max(1e-3, u_spot_cos.x - u_spot_cos.y), 0.0, 1.0);
    e = t * t;
  }
  if (e <= 0.0) discard;
  // Normal-offset lookup (raster/glsl/cube_glsl.h).
  vec3 dp = lookup_offset(v_position, n, dist, cos_x, u_bias_texel, u_vpl_position);
  if (shadowed(u_shadow_frame * dp, length(dp) - u_bias_constant, u_shadow_frame * n)) discard;
  float g = e * cos_x / max(dist2, u_dmin2);
#ifdef IRAD_GLOSSY
  vec3 light = u_vpl_intensity * (g * INV_PI);
  if (u_lobe[3].w > 0.0)
    light *= brdf_lobe_shape(u_lobe[0].rgb, u_lobe[0].a, u_lobe[2].w, u_lobe[1].rgb, u_lobe[1].a,
                             u_vpl_normal, u_lobe[2].xyz, w, u_lobe[3].rgb,
                             sqrt(u_dmin2) / dist); // the clamp's sphere
  vec3 base = material_albedo();
  float metallic, roughness, f90;
  vec3 f0;
  material_brdf(metallic, roughness, f0, f90);
  vec3 weight = u_apply_albedo ? base : vec3(1.0);
  if (!(metallic == 0.0 && f90 == 0.0 && f0 == vec3(0.0))) { // as deferred receiver_weight
    vec3 wo = toward_eye(v_position);
    vec3 nf = brdf_facing_normal(n, wo);
    weight = brdf_receiver(base, metallic, roughness, f0, f90, nf, wo, -w,
                           u_vpl_reachable && roughness < u_traced_roughness);
    if (!u_apply_albedo)
      weight = brdf_over(weight, brdf_albedo(base, metallic, roughness, f0, f90, dot(nf, wo)));
  }
  o_color = vec4(light * weight, 0.0);
#else
  vec3 albedo = u_apply_albedo ? material_albedo() : vec3(1.0);
  o_color = vec4(u_vpl_intensity * (g * INV_PI) * albedo, 0.0);
#endif
}
)";

// Shadow cube faces: distance from the VPL to the nearest surface (with alpha, the nearest
// present one: raster/scene/material_glsl.h, seeded by the VPL's position).
inline constexpr const char* shadow_vertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
#ifdef IRAD_ALPHA
#pragma irad_material_vertex
#endif
uniform mat4 u_face_view_projection;
out vec3 v_position;
void main() {
#ifdef IRAD_ALPHA
  copy_material_attributes();
#endif
  v_position = a_position;
  gl_Position = u_face_view_projection * vec4(a_position, 1.0);
}
)";

inline constexpr const char* shadow_fragment = R"(#version 330 core
in vec3 v_position;
#ifdef IRAD_ALPHA
#pragma irad_material_fragment
#endif
uniform vec3 u_vpl_position;
out vec4 o_distance; // the distance and its gradient per texel (raster/glsl/cube_glsl.h)
void main() {
#ifdef IRAD_ALPHA
  if (material_absent(shadow_alpha_key(u_vpl_position))) discard;
#endif
  float d = length(v_position - u_vpl_position);
  o_distance = vec4(d, dFdx(d), dFdy(d), 0.0);
}
)";

// G-buffer (raster/image/gbuffer.h): the world position (w = 1 where there is a surface), the
// shading normal facing the camera and the albedo. With IRAD_GLOSSY the normal's w holds the
// roughness, the albedo is the directional albedo a(wo) toward the camera (the interleaved
// resolve's demodulation; base for a Lambertian material) with w 1 where the BRDF is not
// Lambertian (0: the shading reads no more), and two more targets hold (base, f90) and
// (f0, metallic). IRAD_LAMBERTIAN_MATERIALS: the program that draws a glossy scene's Lambertian
// materials, the same values without the BRDF's code (llvmpipe runs every branch).
inline constexpr const char* gbuffer_fragment = R"(#version 330 core
in vec3 v_position;
in vec3 v_normal;
#pragma irad_material_fragment
layout(location = 0) out vec4 o_position;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out vec4 o_albedo;
#ifdef IRAD_GLOSSY
#pragma irad_brdf
#pragma irad_brdf_albedo
layout(location = 3) out vec4 o_base;
layout(location = 4) out vec4 o_specular;
#else
uniform vec4 u_eye; // as raster/glsl/brdf_glsl.h declares it
#endif
// 1 while the camera hierarchy's meshes are drawn (raster/passes/camera_lod.h): a triangle seen
// from behind whose smooth normal faces the camera is then a simplified triangle tipped over at
// a silhouette, not the surface's back, and keeps that normal.
uniform int u_simplified;
void main() {
#ifdef IRAD_ALPHA
  if (material_absent(camera_alpha_key())) discard;
#endif
  vec3 n = material_normal(normalize(v_normal));
  vec3 to_eye = u_eye.w > 0.0 ? u_eye.xyz - v_position : u_eye.xyz;
  if (!gl_FrontFacing && !(u_simplified != 0 && dot(v_normal, to_eye) > 0.0)) n = -n;
  o_position = vec4(v_position, 1.0);
#if defined(IRAD_GLOSSY) && defined(IRAD_LAMBERTIAN_MATERIALS)
  // What the lines below write for a Lambertian material (m = f0 = f90 = 0, r = 1), without them.
  vec3 base = material_albedo();
  o_normal = vec4(n, 1.0);
  o_albedo = vec4(base, 0.0);
  o_base = vec4(base, 0.0);
  o_specular = vec4(0.0);
#elif defined(IRAD_GLOSSY)
  vec3 base = material_albedo();
  float metallic, roughness, f90;
  vec3 f0;
  material_brdf(metallic, roughness, f0, f90);
  vec3 wo = toward_eye(v_position);
  float cos_o = dot(brdf_facing_normal(n, wo), wo);
  o_normal = vec4(n, roughness);
  bool lambertian = metallic == 0.0 && f90 == 0.0 && f0 == vec3(0.0);
  o_albedo = vec4(brdf_albedo(base, metallic, roughness, f0, f90, cos_o), lambertian ? 0.0 : 1.0);
  o_base = vec4(base, f90);
  o_specular = vec4(f0, metallic);
#else
  o_normal = vec4(n, 0.0);
  o_albedo = vec4(material_albedo(), 1.0);
#endif
}
)";

// A triangle covering the viewport (no vertex buffer: gl_VertexID) at clip depth u_depth (0
// unless set; the background pass sets 1, the far plane the depth buffer is cleared to).
inline constexpr const char* fullscreen_vertex = R"(#version 330 core
uniform float u_depth;
void main() {
  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  gl_Position = vec4(p, u_depth, 1.0);
}
)";

// Rec. 709 luminance weights (core/environment/environment.h luminance), shared by the deferred
// shading's unsure light (raster/glsl/deferred_shaders.h) and the pass that compares it with the
// pixel's light (raster/image/edge_pixels.h); inserted at "#pragma irad_luminance".
inline constexpr const char* luminance_glsl =
    "const vec3 LUMINANCE = vec3(0.2126, 0.7152, 0.0722);\n";

// The resolve's window (raster/image/interleaved.h), shared by the resolve and the edge-pixel
// pass (raster/image/edge_pixels.h). The including source declares u_position, u_normal, u_size.
inline constexpr const char* resolve_window_glsl = R"(
// Whether pixel q sees the surface that p does (x, n: p's point and normal): on the image, its
// normal m within 18 degrees of n, and the chord d from x to q's point within 5 % of its length
// of the plane normal to n + m. On a flat surface that is p's plane; on a sphere or a cylinder
// the chord is normal to the bisector of the two normals, so a smooth curved mesh is averaged
// as a flat one (with p's plane alone, a sphere a few pixels wide keeps each pixel's own set: the
// k x k pattern of the sets), while creases and steps still cut the window.
bool same_surface(ivec2 q, vec3 x, vec3 n) {
  if (q.x < 0 || q.y < 0 || q.x >= u_size.x || q.y >= u_size.y) return false;
  vec4 xq = texelFetch(u_position, q, 0);
  if (xq.w <= 0.0) return false;
  vec3 m = texelFetch(u_normal, q, 0).xyz;
  if (dot(m, n) < 0.95) return false;
  vec3 d = xq.xyz - x;
  return abs(dot(n + m, d)) <= 0.05 * length(d) * length(n + m);
}
)";

// Interleaved sampling's resolve (Keller & Heidrich 2001): pixel p of a k x k tile was lit by VPL
// set (p.x mod k, p.y mod k) only, its value stored de-interleaved in the atlas. Each set, scaled
// by k^2, estimates the whole sum; p averages the sets of the k x k window around it (offsets
// -h..h, h = k / 2) over the pixels on its own surface (resolve_window_glsl). Where the window is
// cut (a crease, a silhouette, the border) fewer sets are averaged, with unequal weights: still
// an estimate of the whole sum, but a one-sided blur of it, which brightens a crease's row of
// pixels by 2-5 % in the mean of any number of rounds (Cornell box, k = 2). With u_edges those
// pixels are shaded by every set instead (raster/image/edge_pixels.h), and their own sum is
// taken. Then p's albedo.
inline constexpr const char* resolve_fragment = R"(#version 330 core
uniform sampler2D u_atlas;
uniform sampler2D u_position;
uniform sampler2D u_normal;
uniform sampler2D u_albedo;
uniform int u_k;
uniform ivec2 u_tile;   // tile size in the atlas
uniform ivec2 u_size;   // full image size
uniform float u_scale[256]; // per set (core/lights/interleave_sets.h), set = x + k y of its tile
uniform bool u_edges;           // whether the edge pixels' own sums are given:
uniform isampler2D u_edge_at;   // per pixel its texel in u_edge_light (x < 0: not an edge pixel)
uniform sampler2D u_edge_light; // every set's light at the edge pixels (no albedo)
out vec4 o_color;
#pragma irad_resolve_window
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 xp = texelFetch(u_position, p, 0);
  if (xp.w <= 0.0) { o_color = vec4(0.0); return; }
  if (u_edges) {
    ivec2 at = texelFetch(u_edge_at, p, 0).xy;
    if (at.x >= 0) {
      o_color = vec4(texelFetch(u_albedo, p, 0).rgb * texelFetch(u_edge_light, at, 0).rgb, 0.0);
      return;
    }
  }
  vec3 np = texelFetch(u_normal, p, 0).xyz;
  // A window centred on p in which every set has total weight 1: offsets -h..h with h = k/2, the
  // outer rows and columns at half weight when k is even (offsets -h and +h are the same set), so
  // the filter has no half-pixel shift.
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  int h = u_k / 2;
  // q's set and tile coordinates (q % k, q / k) from p's without a division per tap (an integer
  // division per tap and lane makes this pass cost as much as 150 VPL passes on llvmpipe).
  ivec2 pm = p % u_k, pd = p / u_k;
  bool even = (u_k % 2) == 0; // odd k: h = (k - 1) / 2, every tap at full weight
  for (int dy = -h; dy <= h; ++dy)
    for (int dx = -h; dx <= h; ++dx) {
      ivec2 q = p + ivec2(dx, dy);
      if (!same_surface(q, xp.xyz, np)) continue;
      float w = (even && abs(dx) == h ? 0.5 : 1.0) * (even && abs(dy) == h ? 0.5 : 1.0);
      ivec2 m = pm + ivec2(dx, dy); // in (-k, 2k): one wrap at most
      ivec2 below = ivec2(lessThan(m, ivec2(0))), above = ivec2(greaterThanEqual(m, ivec2(u_k)));
      m += (below - above) * u_k;
      float scaled = w * u_scale[m.x + u_k * m.y];
      sum += scaled * texelFetch(u_atlas, m * u_tile + pd - below + above, 0).rgb;
      weight += w;
    }
  vec3 albedo = texelFetch(u_albedo, p, 0).rgb;
  o_color = vec4(albedo * sum * (float(u_k * u_k) / max(weight, 0.25)), 0.0);
}
)";

// Copies a same-size texture into the bound framebuffer (with blending: adds or subtracts it).
inline constexpr const char* copy_fragment = R"(#version 330 core
uniform sampler2D u_source;
out vec4 o_color;
void main() { o_color = texelFetch(u_source, ivec2(gl_FragCoord.xy), 0); }
)";

} // namespace irad::gl::shaders
