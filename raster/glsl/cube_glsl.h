#pragma once
// GLSL shared by the shading passes that look up a VPL's shadow cube (raster/glsl/shaders.h
// vpl_fragment: a cube map; raster/glsl/deferred_shaders.h: the batch's atlas and the cache
// pages), inserted where a source has the line "#pragma irad_cube_lookup".
//
// Each texel of a cube face stores the distance d_c of the nearest surface on the ray through
// its centre and that surface's gradient g = (dd/dx, dd/dy) per face texel (dFdx, dFdy of the
// triangle's own interpolated distance). A receiver looked up at the face point `at` (texels)
// is compared with the plane through the centre, d_c + g . (at - centre): a surface seen at a
// grazing angle theta changes its distance by about dist (2/R) tan(theta) across one texel, far
// more than a thin wall's thickness, so with d_c alone a receiver just behind such a wall but
// nearer than its texel's centre passes (a 2 mm wall lets 2.7e-4 of the lit room's
// light through), and a receiver on the surface itself but farther than the centre is shadowed
// unless the normal offset lifts it over the texel's depth range. The lookup compares the
// receiver with the plane both ways, exact for a planar occluder; the lesser of d_c and the plane
// (the plane only adding shadow) would keep that second need, an offset of 0.75 to a whole
// texel, which darkens receivers in narrow gaps (godot's stacked spheres; raster/passes/
// vpl_shader.h normal_offset_texels has the measurements). Next to a convex edge seen from both
// sides the plane would darken the far face for up to a texel's footprint (the plane
// extended past the edge floats in front of it); there the neighbouring texel sees something
// behind the plane, and that direction's term is dropped (the centre's distance in it).
// Where a texel holds a concave corner (the floor at a wall's foot, seen from the wall's lit
// side), the centre may see the floor and the neighbour the wall: past the line where their
// planes meet, the wall's plane is the nearer surface, and a receiver behind it (the floor on
// the wall's dark side) is shadowed by it, with no help from the normal offset.
#include "raster/context/shader_program.h"

#include <string>

namespace irad::gl::shaders {

inline constexpr const char* cube_lookup_glsl = R"(
// Normal-offset lookup: the receiver x (normal n, at distance dist from the VPL y, cos_x toward
// it) is moved off its surface by u_offset_texels of a shadow texel's footprint there (dist *
// texel angle * sin theta_x), so its own surface never shadows it, while a wall between it and
// the VPL still does (a slope-scaled depth bias lets light through walls thinner than the bias:
// 7 cm at 1 m with 256^2 faces). Returns the moved point relative to y. u_offset_texels:
// raster/passes/vpl_shader.h normal_offset_texels.
uniform float u_offset_texels;
vec3 lookup_offset(vec3 x, vec3 n, float dist, float cos_x, float texel, vec3 y) {
  float sin_x = sqrt(max(1.0 - cos_x * cos_x, 0.0));
  return x + n * (u_offset_texels * dist * texel * sin_x) - y;
}

// The face of direction q (+x, -x, +y, -y, +z, -z: 0..5) and q's coordinates st in [-1, 1] on
// it, GL's cube-map convention.
int cube_face(vec3 q, out vec2 st) {
  vec3 a = abs(q);
  if (a.x >= a.y && a.x >= a.z) {
    st = vec2(q.x > 0.0 ? -q.z : q.z, -q.y) / a.x;
    return q.x > 0.0 ? 0 : 1;
  }
  if (a.y >= a.z) {
    st = vec2(q.x, q.y > 0.0 ? q.z : -q.z) / a.y;
    return q.y > 0.0 ? 2 : 3;
  }
  st = vec2(q.z > 0.0 ? q.x : -q.x, -q.y) / a.z;
  return q.z > 0.0 ? 4 : 5;
}

// The direction (unnormalized) of the point st of face f: cube_face's inverse.
vec3 face_direction(int f, vec2 st) {
  if (f == 0) return vec3(1.0, -st.y, -st.x);
  if (f == 1) return vec3(-1.0, -st.y, st.x);
  if (f == 2) return vec3(st.x, 1.0, st.y);
  if (f == 3) return vec3(st.x, -1.0, -st.y);
  if (f == 4) return vec3(st.x, -st.y, 1.0);
  return vec3(-st.x, -st.y, -1.0);
}

// The steps (+-1 per axis) from the texel of the face point `at` (texels) to the neighbours
// that `at` lies nearer to.
ivec2 toward(vec2 at) {
  vec2 offset = at - (floor(at) + 0.5);
  return ivec2(offset.x >= 0.0 ? 1 : -1, offset.y >= 0.0 ? 1 : -1);
}

// The receiver-plane test of a lookup without the occluder planes (the centre's distance
// alone), for a receiver that lies beyond the surface o which the centre ray of the texel
// `texel` of face `face` (R = res texels per edge) met at distance `centre`: whether o shadows
// it. q: the moved receiver, nq its normal (cube frame, relative to the VPL); f = 2 |q| / R, a
// texel's footprint at the receiver. o does not shadow
//   - where it lies within 2 f of q and less than f in front of the receiver's plane: the
//     receiver's own neighbourhood, its own surface or the other face of a concave crease, which
//     the centre ray meets where the lookup ray meets the receiver;
//   - where it lies behind the receiver's plane, the plane crossing the centre ray within 6 f
//     of q: the receiver's own surface, seen a little farther along the texel.
// So a flat receiver never shadows itself, however grazing the angle, and creases do not shadow
// their faces; the centre's distance alone needs the normal offset to exceed the texel's depth
// range (0.75 of a texel keeps the blocks' contact shadows up to 20 % too bright: raster/passes/
// vpl_shader.h normal_offset_texels). Anything else nearer than the receiver shadows, as does o
// when the plane runs along or away from the centre ray. Both exceptions would carry light under
// a wall thinner than their reach that stands on the receiver's plane: walls thinner than 4 / R
// of the diagonal get the occluder planes instead (raster_renderer.h planes_needed), and
// tests/test_two_rooms measures walls 1.02x and 1.25x that thick (nothing passes; with a 12 f
// reach 1.7e-6 of the lit room does). Measured on the Cornell box (256x256, R = 128, 4 rounds,
// interleave 1, no compensation, 4x4-block relMSE against rt-vpl over the same VPLs): the
// centre's distance alone with 0.75 texel's offset 2.6e-5 (7.1e-5 per pixel); the plane crossing
// alone (0.2 texel, a 6 f reach) 1.48e-5; with the neighbourhood 3.6e-6 (1.1e-5 per pixel). With
// a 12 f reach 2.4e-6, and there f / 2 in front 3.3e-6, 2 f 2.0e-6; within f around 2.5e-6,
// 3 f 2.4e-6. (N = 1024 paths, every VPL, one round, the plane crossing alone: reach 3 f 3.8e-5,
// 6 f 1.65e-5, 12 f 1.49e-5.)
bool in_front_of_receiver(vec3 q, vec3 nq, int face, ivec2 texel, float res, float centre,
                          float bias) {
  vec3 c = normalize(face_direction(face, (vec2(texel) + 0.5) / res * 2.0 - 1.0));
  float f = 2.0 * length(q) / res;
  vec3 o = centre * c;
  if (dot(nq, o - q) < f && distance(o, q) < 2.0 * f) return false;
  float den = dot(nq, c), num = dot(nq, q);
  if (den >= 0.0 || num >= 0.0) return true;
  float e = num / den; // the plane's distance along the centre ray
  if (distance(e * c, q) > 6.0 * f) return true;
  return e > centre + bias;
}

// Whether a lookup's answer is unsure: the receiver (moved, at distance r, normal nq; cube frame)
// lies within a texel of where the map's answer changes, so that the texel's centre ray decides
// for a direction the receiver's own ray may not share (a silhouette's penumbra, a contact). The
// answer of each of the centre and the neighbours toward the lookup point (next_x, next_y; below
// 0 where there is none) is taken as "something lies nearer than the receiver by more than its
// own surface's change across a texel" (f (1 + tan theta): f = 2 |q| / R a texel's footprint,
// theta the receiver's angle to the ray, tan capped at 8); unsure where they differ. The
// shading adds the unsure VPLs' unshadowed light beside the light (raster/image/edge_pixels.h
// lists the pixels where it is a tenth of their light or more, and lib/render.cpp traces them).
// Measured (godot at 128x128, one round, k = 2, R = 64): 14 % of the pixels listed hold 80 % of
// the maps' error against rt-vpl (4x4-block relMSE 2.07e-4 -> 4.2e-5 with them traced); the Cornell
// box at 256x256 (R = 64): 7.6 %, 1.26e-5 -> 3.1e-6.
bool lookup_unsure(vec3 q, vec3 nq, float r, float res, float centre, float next_x,
                   float next_y) {
  float distance_q = length(q);
  float cos_q = abs(dot(nq, q)) / max(distance_q * length(nq), 1e-12);
  float tan_q = sqrt(max(1.0 - cos_q * cos_q, 0.0)) / max(cos_q, 0.125);
  float margin = 2.0 * distance_q / res * (1.0 + tan_q);
  bool here = r - centre > margin;
  return (next_x >= 0.0 && here != (r - next_x > margin)) ||
         (next_y >= 0.0 && here != (r - next_y > margin));
}

// The occluder's distance at the face point `at` (texels) from its texel's stored centre
// distance and gradient: the plane's through the centre. A direction's term counts
// only where the neighbour toward `at` in it (next_x, next_y: its stored distance; below 0 where
// there is none on the face) is not behind the plane at its centre: behind, the occluder ends
// inside the texel (a convex edge seen from both sides) and its plane would float over the
// other face. Same-plane neighbours are within a quarter of a texel's change (distance is not
// linear across the face) and 1e-5 of the distance (rounding). A neighbour in front of the plane
// whose own plane (grad_x, grad_y: its gradient) lies behind the centre's distance at the
// centre, so that the two planes meet between the centres (a concave corner, not a nearer
// object's silhouette), bounds the distance by its plane too. Measured (tests/test_two_rooms,
// the 2 mm wall, k = 2, normal offset 1 texel, the lesser of centre and plane): the leak
// 5.7e-5 -> 3.3e-5 of the lit room; with the plane both ways, 0.5 texel: 4.1e-5.
float occluder_distance(float centre, vec2 gradient, vec2 at, float next_x, vec2 grad_x,
                        float next_y, vec2 grad_y) {
  vec2 step = vec2(toward(at));
  float slack = 0.25 * (abs(gradient.x) + abs(gradient.y)) + 1e-5 * centre;
  vec2 g = gradient;
  if (next_x > centre + g.x * step.x + slack) g.x = 0.0;
  if (next_y > centre + g.y * step.y + slack) g.y = 0.0;
  vec2 offset = clamp(at - (floor(at) + 0.5), vec2(-0.5), vec2(0.5));
  float d = centre + dot(g, offset); // the plane at `at`
  // A neighbour in front of the own plane whose plane meets the own surface between the two
  // centres (a concave corner: a wall on a floor seen from the wall's lit side): beyond the
  // meeting line its surface is the nearer one.
  if (next_x >= 0.0 && next_x < centre + gradient.x * step.x - slack &&
      next_x - grad_x.x * step.x >= centre - slack)
    d = min(d, next_x + dot(grad_x, offset - vec2(step.x, 0.0)));
  if (next_y >= 0.0 && next_y < centre + gradient.y * step.y - slack &&
      next_y - grad_y.y * step.y >= centre - slack)
    d = min(d, next_y + dot(grad_y, offset - vec2(0.0, step.y)));
  return d;
}
)";

// `source` with its "#pragma irad_cube_lookup" line replaced by cube_lookup_glsl.
inline std::string with_cube_lookup(std::string source) {
  insert_glsl(source, "#pragma irad_cube_lookup\n", cube_lookup_glsl);
  return source;
}

} // namespace irad::gl::shaders
