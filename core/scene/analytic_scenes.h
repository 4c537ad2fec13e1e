#pragma once
// The scenes of design.md section 3, built in code, with the answers no estimator of ours
// defines. Each builder validates its input (irad::Error otherwise) and returns a scene with the
// invariants of a loaded one (unit normals, bounds, no zero-area triangles) and one camera.
//
// Integrating sphere. Inside a closed sphere of area A and uniform albedo rho, the form factor
// from any point to a surface element dA is dA / A (cos = r / 2R at both ends, r^2 = 4 R^2 cos^2),
// so every point receives the same irradiance E. Power balance (the patch reflects too):
// E A = Phi + rho E A, hence E = Phi / (A (1 - rho)) and every non-emitting point shows
//     L = rho E / pi = rho Phi / (pi A (1 - rho)),   Phi = pi A_patch L_e (one-sided patch).
// The sphere here is a geodesic polyhedron (an icosahedron, subdivided; flat inward facets). For
// any closed enclosure of uniform albedo the power balance, hence the formula, still holds for
// the area-weighted mean of the reflected radiance over the whole surface (A and A_patch taken
// from the triangles); pointwise it does not, because a facet's form factors differ from dA / A
// (a facet does not see itself, its neighbours are seen at grazing angles). Measured with a
// radiosity solution on the facets (exact point-to-facet form factors at the facet centroids;
// its own power-balance residual is 1e-3 at 1 subdivision, 5e-5 at 4), rho = 0.5, L_e = 1,
// patch angle 0.25, relative deviation from the formula:
//   subdivisions                 1        2        3        4        5
//   triangles                   80      320     1280     5120    20480
//   A / (4 pi R^2)          0.9283   0.9812   0.9952   0.9988   0.9997
//   A_patch / A            0.05970  0.01461  0.01460  0.01651  0.01582
//   answer L               0.05970  0.01461  0.01460  0.01651  0.01582  (= A_patch / A here)
//   far wall, mean          -0.6 %   -0.08 %  -0.02 %  -0.001 % -0.001 %
//   far wall, points        -3.9 %   -2.1 %   -1.3 %   -0.65 %  -0.33 %
//                           +1.7 %   +2.2 %   +1.1 %   +0.60 %  +0.32 %
//   all facet centroids     -3.4 %   -9.0 %   -3.8 %   -1.6 %   -0.84 %
//    (outside the patch)    +2.9 %   +2.6 %   +2.3 %   +1.2 %   +0.73 %
// ("far wall": 7 points per facet, centroid, near the corners and edges, on the facets within
// 0.6 rad of the pole -z, which the camera sees). The pointwise deviation halves with each
// subdivision (it goes with the edge length); the answer itself moves with the tessellation
// mainly through which triangles make up the patch (A_patch), which the formula accounts for.
// Default: 4 subdivisions, where the far wall is within +-0.65 % of the answer point by point
// and within 1e-5 on average, below the noise of any image we compare at (the path tracer's
// pixels are 1.9 % RMS at 256 spp), for a scene of 5120 triangles (0.6 MB as glTF).
//
// Furnace box: a closed box whose every surface emits L_e and has albedo rho: L = L_e / (1 - rho)
// everywhere (exact for any closed enclosure).
//
// Square light over a plane: direct light only (the light's albedo is 0, the plane cannot see
// itself): a point x of the plane shows rho E(x) / pi, E from Lambert's polygon formula.
#include "core/scene/scene.h"

#include <glm/glm.hpp>
#include <optional>

namespace irad {

struct AnalyticScene {
  Scene scene; // with one camera
  // The radiance every non-emitting point shows (integrating sphere, furnace box); nullopt when
  // the answer varies from point to point (square light: see square_light_radiance()).
  std::optional<double> expected_radiance;
};

constexpr int kDefaultSphereSubdivisions = 4;
constexpr int kMaxSphereSubdivisions = 8;
constexpr double kDefaultPatchAngle = 0.25; // radians

// The interior of a geodesic sphere of radius `radius` centred at the origin: an icosahedron with
// vertices at the poles (0, 0, +-radius), each triangle split into four `subdivisions` times with
// the new vertices pushed onto the sphere (20 * 4^subdivisions triangles). Triangles face the
// centre (counter-clockwise seen from it) with flat normals (each triangle has its own three
// vertices): per-vertex normals pointing to the centre would make the shading normal differ from
// the geometric one, and the estimators' cosines would no longer integrate to pi over the closed
// polyhedron, which breaks the power balance the answer rests on. The emitting patch (radiance
// `patch_radiance`, one-sided, albedo `albedo` like every other triangle) is made of the
// triangles around the pole +z: those touching it, and those whose centroid lies within
// `patch_angle` of it. Material 0 "wall", material 1 "patch". The camera "inside" stands near the
// centre (a little off it) and looks at the pole -z, opposite the patch.
// Requires radius > 0, albedo in [0, 1), 0 <= subdivisions <= kMaxSphereSubdivisions,
// patch_radiance > 0, 0 < patch_angle < pi/2.
AnalyticScene integrating_sphere(double radius, double albedo,
                                 int subdivisions = kDefaultSphereSubdivisions,
                                 double patch_radiance = 1.0,
                                 double patch_angle = kDefaultPatchAngle);

// rho Phi / (pi A (1 - rho)) for a closed scene of uniform grey albedo rho < 1 and emitting
// triangles of total power Phi = sum pi A_k mean(L_e,k) (2 pi for double-sided ones), with A the
// total area of all triangles, in double precision from the stored vertices. Throws when the
// scene has no emitter, textures, punctual lights, or albedos that differ or are not grey.
// It does not check that the scene is closed or spherical.
double integrating_sphere_radiance(const Scene& scene);

// The closed box [0, size]^3, six walls facing inward, every one with albedo `albedo` and
// emitted radiance `emission` (material 0 "wall"). The camera "inside" stands near the wall
// z = size, off the box's axis (a pixel centre on a seam of two walls is a degenerate point),
// and looks at the wall z = 0. Requires size > 0, albedo in [0, 1), emission > 0.
AnalyticScene furnace_box(double size, double albedo, double emission);

// Square light over a plane (see square_light_over_plane in core/scene/scene_builder.h).
struct SquareLight {
  double side = 1.0;       // of the light
  double height = 1.0;     // of the light over the plane z = 0
  double radiance = 1.0;   // of the light, > 0
  double plane_side = 6.0; // of the receiving plane, centred at the origin
  double albedo = 0.5;     // of the plane, in [0, 1]
};

// The scene, with the camera "below-light" at (0, 0, height / 2) looking straight down (image up
// +y, yfov 1.6) at the plane under the light. expected_radiance is nullopt.
AnalyticScene square_light(const SquareLight& light);

// The radiance the plane shows at x = (x, y, 0): albedo E(x) / pi with Lambert's formula, and 0
// outside the plane's square.
double square_light_radiance(const SquareLight& light, const glm::dvec3& x);

} // namespace irad
