#pragma once
// GLSL for mirrored VPLs (core/scene/mirrors.h), kept apart from raster/glsl/shaders.h so that
// the programs of scenes without mirrors hold no mirror code.
#include <string>

namespace irad::gl::shaders {

// The mirrored VPL's pyramid: x is lit only if it lies on the lit side of the mirror plane
// (n, w), n toward the lit side, and the segment from the VPL y (behind the plane) to x crosses
// the plane inside one of the polygon's `triangles` triangles, whose corners the including
// source names MIRROR_CORNER(i) (3 per triangle). Shared by the per-VPL pass (below) and the
// deferred passes (raster/glsl/deferred_shaders.h, the corners in a texture).
inline constexpr const char* mirror_pyramid_glsl = R"(
bool inside_pyramid(vec3 x, vec3 y, vec4 plane, int triangles) {
  float sx = dot(plane.xyz, x) + plane.w;
  float sy = dot(plane.xyz, y) + plane.w;
  if (!(sx > 0.0) || !(sy < 0.0)) return false;
  vec3 m = y + (sy / (sy - sx)) * (x - y);
  for (int k = 0; k < triangles; ++k) {
    vec3 a = MIRROR_CORNER(3 * k), b = MIRROR_CORNER(3 * k + 1), c = MIRROR_CORNER(3 * k + 2);
    vec3 n = cross(b - a, c - a);
    if (dot(cross(b - a, m - a), n) >= 0.0 && dot(cross(c - b, m - b), n) >= 0.0 &&
        dot(cross(a - c, m - c), n) >= 0.0)
      return true;
  }
  return false;
}
)";

// The per-VPL pass's test: the polygon in uniforms. Inserted into vpl_fragment before main();
// needs u_vpl_position.
inline constexpr const char* mirror_clip_uniforms = R"(
uniform vec4 u_mirror_plane;      // (n, w), n toward the lit side
uniform int u_mirror_triangles;   // triangles of the polygon (<= 16)
uniform vec3 u_mirror_corners[48];
#define MIRROR_CORNER(i) u_mirror_corners[i]
)";
inline constexpr const char* mirror_clip_call = R"(
bool through_mirror(vec3 x) {
  return inside_pyramid(x, u_vpl_position, u_mirror_plane, u_mirror_triangles);
}
)";

// vpl_fragment with the pyramid test as the first statement of main(). Throws std::logic_error
// if vpl_fragment does not have the expected shape.
std::string mirror_vpl_fragment(const char* vpl_fragment);

// Shadow cube of a mirrored VPL y' (the image of y): the world as the unfolded path y' -> m -> x
// sees it. Drawn twice: the real scene (u_reflect = identity; blocks m -> x) and the scene
// reflected in the mirror plane (blocks y -> m, seen from y' as its reflection), both clipped to
// the real side of the plane (gl_ClipDistance from the unreflected position), so whatever lies
// behind the mirror is ignored. The fragment shader is shadow_fragment.
inline constexpr const char* mirror_shadow_vertex = R"(#version 330 core
layout(location = 0) in vec3 a_position;
#ifdef IRAD_ALPHA
#pragma irad_material_vertex
#endif
uniform mat4 u_face_view_projection;
uniform mat4 u_reflect;
uniform vec4 u_clip_plane;
out vec3 v_position;
void main() {
#ifdef IRAD_ALPHA
  copy_material_attributes();
#endif
  gl_ClipDistance[0] = dot(u_clip_plane, vec4(a_position, 1.0));
  v_position = (u_reflect * vec4(a_position, 1.0)).xyz;
  gl_Position = u_face_view_projection * vec4(v_position, 1.0);
}
)";

} // namespace irad::gl::shaders
