#pragma once
// GLSL of the distant environment (core/environment/environment.h), written once: the map lookup
// L(w) and the visible suns' disks, for every program that shows what camera rays see past the
// scene (raster/passes/background.h). The formulas are core/environment/environment.cpp's
// (Environment::map_coordinates, texel_of, to_map), so the raster's background and the CPU
// estimators agree texel for texel.
namespace irad::gl::shaders {

// L(w) for a unit world direction w, nearest texel, strength applied:
//   d = R_y(-rotation) w = (c w.x - s w.z, w.y, s w.x + c w.z), (c, s) = (cos, sin) rotation;
//   u = 1/2 + atan(d.z, d.x) / (2 pi), v = acos(d.y) / pi (computed as atan(|d.xz|, d.y) / pi);
//   texel (clamp(floor(u W), 0, W - 1), clamp(floor(v H), 0, H - 1)), row 0 the zenith.
// texelFetch: no filtering or wrap mode is involved.
inline constexpr const char* environment_lookup = R"(
// The map as stored, row 0 at the top, in IRAD_ENVIRONMENT_BANDS horizontal bands of
// u_environment_band_rows rows (the last may have fewer), top first: llvmpipe holds at most
// 1 GiB in one texture, a 16384 x 8192 RGB32F map 1.5 GiB.
uniform sampler2D u_environment[IRAD_ENVIRONMENT_BANDS];
uniform ivec2 u_environment_size;
uniform int u_environment_band_rows;
uniform vec2 u_environment_rotation; // (cos, sin) of the rotation about +Y
uniform float u_environment_strength;
const float ENVIRONMENT_PI = 3.14159265358979324;
ivec2 environment_texel(vec3 d) {
  ivec2 size = u_environment_size;
  float u = 0.5 + atan(d.z, d.x) / (2.0 * ENVIRONMENT_PI);
  // acos(d.y) as atan(|d.xz|, d.y), equal for unit d: GLSL's acos is far less precise (on
  // llvmpipe rows come out one off 1.2e-4 rad from their border), atan's error is the same as u's.
  float v = atan(length(d.xz), d.y) / ENVIRONMENT_PI;
  ivec2 t = ivec2(floor(vec2(u, v) * vec2(size)));
  return clamp(t, ivec2(0), size - 1);
}
vec3 environment_radiance(vec3 w) {
  float c = u_environment_rotation.x, s = u_environment_rotation.y;
  vec3 d = vec3(c * w.x - s * w.z, w.y, s * w.x + c * w.z);
  ivec2 t = environment_texel(d);
  int band = t.y / u_environment_band_rows;
  ivec2 local = ivec2(t.x, t.y - band * u_environment_band_rows);
  vec3 l = texelFetch(u_environment[0], local, 0).rgb; // samplers: constant indices only (3.30)
#if IRAD_ENVIRONMENT_BANDS > 1
  if (band == 1) l = texelFetch(u_environment[1], local, 0).rgb;
#endif
#if IRAD_ENVIRONMENT_BANDS > 2
  if (band == 2) l = texelFetch(u_environment[2], local, 0).rgb;
#endif
#if IRAD_ENVIRONMENT_BANDS > 3
  if (band == 3) l = texelFetch(u_environment[3], local, 0).rgb;
#endif
  return u_environment_strength * l;
}
)";

// The visible suns (core/scene/scene.h PunctualLight::angular_radius): IRAD_SUNS > 0 disks, sun k
// seen where dot(w, toward_k) >= cos r_k with uniform radiance E_k / (pi sin^2 r_k); disks that
// overlap add.
inline constexpr const char* sun_disks = R"(
uniform vec3 u_sun_toward[IRAD_SUNS];   // unit, from the scene toward the sun: -direction
uniform float u_sun_cos[IRAD_SUNS];     // cos r
uniform vec3 u_sun_radiance[IRAD_SUNS]; // E / (pi sin^2 r)
vec3 sun_radiance(vec3 w) {
  vec3 sum = vec3(0.0);
  for (int k = 0; k < IRAD_SUNS; ++k)
    if (dot(w, u_sun_toward[k]) >= u_sun_cos[k]) sum += u_sun_radiance[k];
  return sum;
}
)";

// What the camera ray through the pixel centre sees past the scene: L_env(w) (IRAD_ENVIRONMENT)
// plus the sun disks (IRAD_SUNS > 0). The ray is core/camera/view.cpp's image_point_ray at the
// pixel centre, (x, y) in image pixels with y down, through u_inverse_view_projection (jittered:
// the jittered projection's inverse, so the ray passes through the jittered point). Appended to the
// #version line, the defines and the functions above (raster/passes/background.cpp).
inline constexpr const char* background_fragment = R"(
uniform mat4 u_inverse_view_projection;
uniform vec2 u_size;     // the image's width and height in pixels
uniform vec3 u_eye;      // perspective: the camera's position
uniform vec3 u_forward;  // orthographic: the direction of every ray
uniform bool u_orthographic;
out vec4 o_color;
vec3 camera_ray() {
  if (u_orthographic) return u_forward;
  float x = gl_FragCoord.x, y = u_size.y - gl_FragCoord.y;
  float nx = x / u_size.x * 2.0 - 1.0, ny = 1.0 - y / u_size.y * 2.0;
  vec4 far = u_inverse_view_projection * vec4(nx, ny, 1.0, 1.0);
  return normalize(far.xyz / far.w - u_eye);
}
void main() {
  vec3 w = camera_ray();
  vec3 l = vec3(0.0);
#ifdef IRAD_ENVIRONMENT
  l += environment_radiance(w);
#endif
#if IRAD_SUNS > 0
  l += sun_radiance(w);
#endif
  o_color = vec4(l, 0.0);
}
)";

} // namespace irad::gl::shaders
