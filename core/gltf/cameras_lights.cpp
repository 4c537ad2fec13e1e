#include "core/gltf/cameras_lights.h"

#include <cmath>
#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

namespace irad::gltf {

namespace {

constexpr double kPi = 3.14159265358979323846;

void validate_perspective(const Context& ctx, const tinygltf::PerspectiveCamera& p,
                          const std::string& where) {
  if (!(std::isfinite(p.yfov) && p.yfov > 0.0 && p.yfov < kPi)) {
    ctx.fail(where, fmt::format("yfov must be > 0 and < pi, got {}", p.yfov));
  }
  if (!(std::isfinite(p.znear) && p.znear > 0.0)) {
    ctx.fail(where, fmt::format("znear must be > 0, got {}", p.znear));
  }
  if (p.zfar != 0.0 && !(std::isfinite(p.zfar) && p.zfar > p.znear)) {
    ctx.fail(where, fmt::format("zfar must be > znear, got {}", p.zfar));
  }
  if (p.aspectRatio != 0.0 && !(std::isfinite(p.aspectRatio) && p.aspectRatio > 0.0)) {
    ctx.fail(where, fmt::format("aspectRatio must be > 0, got {}", p.aspectRatio));
  }
}

// Light colour (default white), every component finite and >= 0.
glm::dvec3 light_color(const Context& ctx, const tinygltf::Light& l, const std::string& where) {
  if (l.color.empty()) return glm::dvec3(1.0);
  if (l.color.size() != 3) ctx.fail(where, "color must have 3 components");
  for (double c : l.color) {
    if (!(std::isfinite(c) && c >= 0.0)) ctx.fail(where, "color must be finite and >= 0");
  }
  return {l.color[0], l.color[1], l.color[2]};
}

// The light in its node's frame, validated; position and direction are set by place_light().
PunctualLight convert_light(const Context& ctx, const tinygltf::Light& l,
                            const std::string& where) {
  PunctualLight out;
  out.kind = l.type == "spot"          ? PunctualLight::Kind::Spot
             : l.type == "directional" ? PunctualLight::Kind::Directional
                                       : PunctualLight::Kind::Point;
  if (!(std::isfinite(l.intensity) && l.intensity >= 0.0)) {
    ctx.fail(where, fmt::format("intensity must be finite and >= 0, got {}", l.intensity));
  }
  out.intensity = glm::vec3(light_color(ctx, l, where) * l.intensity);
  if (!std::isfinite(out.intensity.x + out.intensity.y + out.intensity.z)) {
    ctx.fail(where, "color * intensity overflows");
  }
  if (!(std::isfinite(l.range) && l.range >= 0.0)) ctx.fail(where, "range must be > 0");
  if (l.range > 0.0) ctx.warn("the range of KHR_lights_punctual lights is ignored");
  if (out.kind == PunctualLight::Kind::Spot) {
    const double inner = l.spot.innerConeAngle;
    const double outer = l.spot.outerConeAngle;
    if (!(inner >= 0.0 && inner < outer && outer <= 0.5 * kPi)) {
      ctx.fail(where, fmt::format("spot cone angles must satisfy 0 <= innerConeAngle ({}) < "
                                  "outerConeAngle ({}) <= pi/2",
                                  inner, outer));
    }
    out.inner_cone = float(inner);
    out.outer_cone = float(outer);
  }
  return out;
}

} // namespace

std::optional<Camera> place_camera(const Context& ctx, std::size_t camera, std::size_t node,
                                   const glm::dmat4& world) {
  const tinygltf::Camera& c = ctx.model.cameras[camera];
  const std::string where = element("cameras", camera);
  if (c.type != "perspective") {
    ctx.warn("orthographic cameras are not supported; skipped");
    return std::nullopt;
  }
  const tinygltf::PerspectiveCamera& p = c.perspective;
  validate_perspective(ctx, p, where);
  const std::optional<glm::mat4> frame = camera_frame_of(world);
  if (!frame) ctx.fail(element("nodes", node), "the camera's node transform is singular");
  Camera out;
  out.name = !c.name.empty() ? c.name : "camera" + std::to_string(camera);
  out.camera_to_world = *frame;
  out.yfov = float(p.yfov);
  if (p.aspectRatio != 0.0) out.aspect = float(p.aspectRatio);
  out.znear = float(p.znear);
  if (p.zfar != 0.0) out.zfar = float(p.zfar);
  return out;
}

std::optional<PunctualLight> place_light(const Context& ctx, std::size_t light, std::size_t node,
                                         const glm::dmat4& world) {
  const tinygltf::Light& l = ctx.model.lights[light];
  const std::string where = "KHR_lights_punctual.lights[" + std::to_string(light) + "]";
  if (l.type != "point" && l.type != "spot" && l.type != "directional") {
    ctx.fail(where, "unknown light type '" + l.type + "'");
  }
  PunctualLight out = convert_light(ctx, l, where);
  out.name = !l.name.empty() ? l.name : "light" + std::to_string(light);
  out.position = glm::vec3(world[3]);
  const glm::dvec3 axis = -glm::dvec3(world[2]);
  const double len = glm::length(axis);
  if (len > 0.0 && std::isfinite(len)) {
    out.direction = glm::vec3(axis / len);
  } else if (out.kind != PunctualLight::Kind::Point) {
    ctx.fail(element("nodes", node), "the light's node transform is singular (no direction)");
  }
  return out;
}

Camera default_camera(const Bounds& bounds) {
  Camera out;
  out.name = "default";
  const double radius = 0.5 * double(bounds.diagonal());
  const double distance = radius / std::sin(0.5 * double(out.yfov));
  const glm::dvec3 eye = glm::dvec3(bounds.center()) + glm::dvec3(0.0, 0.0, distance);
  out.camera_to_world = glm::mat4(glm::translate(glm::dmat4(1.0), eye));
  return out;
}

} // namespace irad::gltf
