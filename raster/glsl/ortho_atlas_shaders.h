#pragma once
// GLSL 3.30 core sources of the orthographic shadow atlas (raster/shadow/ortho_atlas.h): instance
// i draws the map of direction i of the batch into its tile. The body gets the version line and
// the array size from batched_source (raster/glsl/batched_shaders.h).
namespace irad::gl::shaders {

// Clip coordinates of OrthoShadow's map (x, y over the square around the bounds' centre, z the
// depth along d over the bounding sphere, in [-1, 1]), moved into the tile: the tile's pixels
// p = (ndc + 1) M / 2 + u_origin[i] of an atlas of u_atlas_size pixels. The bounding sphere lies
// inside [-1, 1]^2, so nothing reaches a neighbouring tile.
inline constexpr const char* ortho_atlas_vertex = R"(
layout(location = 0) in vec3 a_position;
#ifdef IRAD_ALPHA
#pragma irad_material_vertex
#endif
layout(std140) uniform OrthoBatch {
  mat4 u_light_clip[MAX_BATCH];
  vec4 u_origin[MAX_BATCH];   // xy: the tile's first pixel; zw unused
  vec4 u_direction[MAX_BATCH];
};
uniform float u_tile_size;    // M
uniform vec2 u_atlas_size;    // in pixels
#ifdef IRAD_ALPHA
out vec3 v_position;
flat out vec3 v_direction;
#endif
void main() {
  int i = gl_InstanceID;
#ifdef IRAD_ALPHA
  copy_material_attributes();
  v_position = a_position;
  v_direction = u_direction[i].xyz;
#endif
  vec4 c = u_light_clip[i] * vec4(a_position, 1.0);  // w = 1
  vec2 p = (c.xy + 1.0) * (0.5 * u_tile_size) + u_origin[i].xy;
  gl_Position = vec4(2.0 * p / u_atlas_size - 1.0, c.z, 1.0);
}
)";

// Depth only (the window depth (z + 1) / 2 of the nearest surface); with alpha, absent fragments
// (raster/scene/material_glsl.h) are seeded by the direction, as OrthoShadow's.
inline constexpr const char* ortho_atlas_fragment = R"(
#ifdef IRAD_ALPHA
in vec3 v_position;
flat in vec3 v_direction;
#pragma irad_material_fragment
#endif
void main() {
#ifdef IRAD_ALPHA
  if (material_absent(shadow_alpha_key(v_direction))) discard;
#endif
}
)";

} // namespace irad::gl::shaders
