#pragma once
// Planar mirrors (seed section 5.1.2) and the mirrored VPLs through which light reaches diffuse
// surfaces by way of a mirror.
//
// A mirror is a triangle whose material is specular (core/scene/scene.h): a perfect mirror on both
// faces with reflectance R = base_color (a mirror's baseColorTexture is ignored everywhere, so
// that every estimator uses the same R). Mirror triangles are grouped into MirrorPolygons: the
// coplanar triangles of one material, at most max_triangles per polygon (a larger plane is split
// into several polygons; they partition the plane, so the light through them adds up).
//
// The estimator. A VPL at y (core/lights/vpl.h: C(x) = I E(y, x) cos_x / d^2 V rho(x)/pi) also
// lights x by way of the plane of mirror polygon P: the ray leaves y toward the point m where the
// segment y' -> x crosses the plane (y' = y reflected in the plane), and the path y -> m -> x has
// length |x - y'| and leaves y along the reflection of (x - y') in the plane. So that light is
// exactly a VPL at y' with the reflected normal and intensity R I (the mirrored VPL), which lights
// x only when x lies on y's side of the plane, m lies inside P, and both y -> m and m -> x are
// free. This is a deterministic connection, like the one of an ordinary VPL to x, so every VPL gets
// a mirrored copy for every polygon that its emission can reach (the seed mirrors only the light of
// the particle that hit the mirror: that copy would have to be weighted by 1 / P(the particle hits
// P), which has no closed form under occlusion). Light that meets two or more mirrors between y and
// x is not connected (a path through one plane cannot meet that plane again, so scenes with one
// mirror plane lose nothing); the particles themselves reflect in any number of mirrors
// (walk/vpls/quasi_random_walk.h).
#include "core/lights/vpl.h"
#include "core/scene/mirror_polygon.h"
#include "core/scene/scene.h"

#include <glm/glm.hpp>
#include <optional>
#include <vector>

namespace irad {

// The mirror polygons of a scene (empty when it has no specular material), in triangle order:
// a pure function of the scene, so the walk, the raster and rt-vpl agree on the indices.
std::vector<MirrorPolygon> find_mirrors(const Scene& scene);

inline float plane_distance(const glm::vec4& plane, const glm::vec3& p) {
  return glm::dot(glm::vec3(plane), p) + plane.w;
}
inline glm::vec3 reflect_point(const glm::vec4& plane, const glm::vec3& p) {
  return p - 2.0f * plane_distance(plane, p) * glm::vec3(plane);
}
inline glm::vec3 reflect_direction(const glm::vec3& n, const glm::vec3& d) {
  return d - 2.0f * glm::dot(n, d) * n;
}

// The mirrored copy of `vpl` in polygon `index` of `mirrors`, or nothing when its light cannot
// reach the polygon's front (the VPL lies in the plane, or a one-sided surface VPL faces away from
// every corner; a directional VPL is never mirrored). The copy has Vpl::mirror = index and
// Vpl::mirror_plane = the plane oriented toward the original VPL (the side it lights).
std::optional<Vpl> mirrored_vpl(const Vpl& vpl, const std::vector<MirrorPolygon>& mirrors,
                                std::size_t index);

// For a mirrored VPL: the point m where the segment from it to x crosses its mirror plane, when
// x lies on the lit side and m inside the polygon; otherwise nothing.
std::optional<glm::vec3> mirror_crossing(const Vpl& vpl, const MirrorPolygon& mirror,
                                         const glm::vec3& x);

// Whether the point m of the polygon's plane lies inside one of its triangles.
bool inside_polygon(const MirrorPolygon& mirror, const glm::vec3& m);

} // namespace irad
