#pragma once
// Perfect mirrors (core/scene/mirrors.h) on the Embree side: following a ray through them, the
// mirrored copies the walk adds beside each VPL, and the visibility of a mirrored VPL.
#include "core/lights/vpl.h"
#include "core/scene/mirrors.h"
#include "core/scene/scene.h"
#include "walk/rays/ray_scene.h"

#include <optional>
#include <vector>

namespace irad {

// Reflections followed in a row before a ray is given up (two facing mirrors): its light is lost.
inline constexpr int max_mirror_bounces = 16;

// The first non-mirror surface along origin + t dir (t > 0), reflecting in every mirror on the way:
// `origin` and `dir` become the ray that reaches it (origin + hit.t dir is the hit point) and
// `throughput` is multiplied by each mirror's reflectance R. Nothing when the ray leaves the scene
// or exceeds max_mirror_bounces. eps: the scene's ray offset (a reflected ray starts eps off the
// mirror, on the side it came from).
std::optional<RayHit> trace_through_mirrors(const Scene& scene, const RayScene& rays,
                                            glm::vec3& origin, glm::vec3& dir,
                                            glm::vec3& throughput, float eps);

// Appends the mirrored copy of `vpl` in every polygon it can reach (core/scene/mirrors.h). By
// value: `vpl` may be an element of `out`.
void append_mirrored(Vpl vpl, const std::vector<MirrorPolygon>& mirrors, std::vector<Vpl>& out);

// Whether the mirrored VPL `vpl` reaches x: x on the lit side, the crossing m inside the polygon,
// and the segments y -> m (y the original VPL) and m -> x free.
bool mirrored_visible(const RayScene& rays, const Vpl& vpl, const MirrorPolygon& mirror,
                      const glm::vec3& x, float eps);

} // namespace irad
