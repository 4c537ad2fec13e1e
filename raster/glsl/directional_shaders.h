#pragma once
// GLSL 3.30 core sources of the directional lights' passes (raster/passes/directional_pass.h).
namespace irad::gl::shaders {

// Orthographic shadow map: the depth of the nearest surface along the light's travel d,
// dot(p - c, d) in world units (c: the centre of the scene's bounds).
inline constexpr const char* ortho_shadow_vertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
#ifdef IRAD_ALPHA
#pragma irad_material_vertex
#endif
uniform mat4 u_light_clip;
out vec3 v_position;
void main() {
#ifdef IRAD_ALPHA
  copy_material_attributes();
#endif
  v_position = a_position;
  gl_Position = u_light_clip * vec4(a_position, 1.0);
}
)";

inline constexpr const char* ortho_shadow_fragment = R"(#version 330 core
in vec3 v_position;
#ifdef IRAD_ALPHA
#pragma irad_material_fragment
#endif
uniform vec3 u_centre;
uniform vec3 u_direction;
out float o_depth;
void main() {
#ifdef IRAD_ALPHA
  if (material_absent(shadow_alpha_key(u_direction))) discard;
#endif
  o_depth = dot(v_position - u_centre, u_direction);
}
)";

// One directional VPL's w * C(x) = I max(0, n . -d) V rho(x)/pi (core/lights/vpl.h), added by
// blending.
inline constexpr const char* directional_fragment = R"(#version 330 core
in vec3 v_position;
in vec3 v_normal;
#pragma irad_material_fragment
uniform vec3 u_direction;        // d, where the light travels (unit)
uniform vec3 u_intensity;        // w * E
uniform sampler2D u_shadow;      // depth along d of the nearest surface
uniform mat4 u_light_lookup;     // world -> (shadow map uv, depth along d)
uniform float u_bias_constant;   // scale-relative
uniform float u_texel;           // a shadow texel's width in world units
uniform bool u_apply_albedo;     // false: irradiance / pi only (interleaved mode multiplies later)
out vec4 o_color;
const float INV_PI = 0.31830988618379067;
void main() {
#ifdef IRAD_ALPHA
  if (material_absent(camera_alpha_key())) discard;
#endif
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  float cos_x = dot(n, -u_direction);
  if (cos_x <= 0.0) discard;
  // Normal offset by a texel's width times sin theta_x: the receiver's own plane then lies at
  // least 0.71 texel * tan theta_x behind it along d, more than it falls across the half-texel
  // diagonal between the receiver and the texel centre the lookup reads.
  float sin_x = sqrt(max(1.0 - cos_x * cos_x, 0.0));
  vec3 s = (u_light_lookup * vec4(v_position + n * (u_texel * sin_x), 1.0)).xyz;
  if (s.z > texture(u_shadow, s.xy).r + u_bias_constant) discard;
  vec3 albedo = u_apply_albedo ? material_albedo() : vec3(1.0);
  o_color = vec4(u_intensity * (cos_x * INV_PI) * albedo, 0.0);
}
)";

} // namespace irad::gl::shaders
