#pragma once
// Internal to the glTF loader: perspective cameras and KHR_lights_punctual lights placed by nodes.
#include "core/gltf/context.h"
#include "core/scene/scene.h"

#include <optional>

namespace irad::gltf {

// cameras[camera] placed by nodes[node] with world matrix `world`: camera_to_world is `world`
// with scale and shear removed (Gram-Schmidt keeping the -z viewing axis, right-handed).
// Fails unless 0 < yfov < pi, znear > 0, zfar > znear (if set), aspectRatio > 0 (if set).
// Orthographic cameras: fails unless xmag and ymag are finite and non-zero, znear >= 0 and
// zfar > znear.
std::optional<Camera> place_camera(const Context& ctx, std::size_t camera, std::size_t node,
                                   const glm::dmat4& world);

// KHR_lights_punctual lights[light] placed by nodes[node]: position = world * (0, 0, 0, 1),
// direction = normalised world * (0, 0, -1, 0), intensity = color * intensity. Fails unless
// color and intensity are finite and >= 0 and 0 <= innerConeAngle < outerConeAngle <= pi/2.
// Point, spot and directional lights; a range is ignored with a warning.
std::optional<PunctualLight> place_light(const Context& ctx, std::size_t light, std::size_t node,
                                         const glm::dmat4& world);

// Camera "default": looks down -z at the centre of `bounds` from the +z side, at the distance at
// which the bounding sphere (radius diagonal / 2) fits in the vertical field of view
// (0.6911 rad): d = r / sin(yfov / 2). Aspect unset.
Camera default_camera(const Bounds& bounds);

} // namespace irad::gltf
