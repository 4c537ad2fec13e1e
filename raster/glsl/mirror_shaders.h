#pragma once
// GLSL for mirrored VPLs (core/mirrors.h), kept apart from raster/glsl/shaders.h so that scenes
// without mirrors run the very same programs as before.
#include <string>

namespace irad::gl::shaders {

// The mirrored VPL's pyramid: x is lit only if it lies on the lit side of the mirror plane and
// the segment from the VPL (u_vpl_position, behind the plane) to x crosses the plane inside one
// of the polygon's triangles. Inserted into vpl_fragment before main(); needs u_vpl_position.
inline constexpr const char* mirror_clip_functions = R"(
uniform vec4 u_mirror_plane;      // (n, w), n toward the lit side
uniform int u_mirror_triangles;   // triangles of the polygon (<= 16)
uniform vec3 u_mirror_corners[48];
bool through_mirror(vec3 x) {
  float sx = dot(u_mirror_plane.xyz, x) + u_mirror_plane.w;
  float sy = dot(u_mirror_plane.xyz, u_vpl_position) + u_mirror_plane.w;
  if (!(sx > 0.0) || !(sy < 0.0)) return false;
  vec3 m = u_vpl_position + (sy / (sy - sx)) * (x - u_vpl_position);
  for (int k = 0; k < u_mirror_triangles; ++k) {
    vec3 a = u_mirror_corners[3 * k], b = u_mirror_corners[3 * k + 1];
    vec3 c = u_mirror_corners[3 * k + 2];
    vec3 n = cross(b - a, c - a);
    if (dot(cross(b - a, m - a), n) >= 0.0 && dot(cross(c - b, m - b), n) >= 0.0 &&
        dot(cross(a - c, m - c), n) >= 0.0)
      return true;
  }
  return false;
}
)";

// vpl_fragment with the pyramid test as the first statement of main(). Throws std::logic_error
// if vpl_fragment no longer has the expected shape.
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
