#include "core/gltf/read/cameras_lights.h"

#include "core/gltf/read/nodes.h"

#include <cmath>
#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

namespace irad::gltf {

namespace {

constexpr double kPi = 3.14159265358979323846;

void validate_perspective(const Context& ctx, const json& p, const std::string& where) {
  const double yfov = number_member(p, "yfov", 0.0);
  const double znear = number_member(p, "znear", 0.0);
  const double zfar = number_member(p, "zfar", 0.0);
  const double aspect = number_member(p, "aspectRatio", 0.0);
  if (!(std::isfinite(yfov) && yfov > 0.0 && yfov < kPi)) {
    ctx.fail(where, fmt::format("yfov must be > 0 and < pi, got {}", yfov));
  }
  if (!(std::isfinite(znear) && znear > 0.0)) {
    ctx.fail(where, fmt::format("znear must be > 0, got {}", znear));
  }
  if (zfar != 0.0 && !(std::isfinite(zfar) && zfar > znear)) {
    ctx.fail(where, fmt::format("zfar must be > znear, got {}", zfar));
  }
  if (aspect != 0.0 && !(std::isfinite(aspect) && aspect > 0.0)) {
    ctx.fail(where, fmt::format("aspectRatio must be > 0, got {}", aspect));
  }
}

void validate_orthographic(const Context& ctx, const json& o, const std::string& where) {
  const double xmag = number_member(o, "xmag", 0.0);
  const double ymag = number_member(o, "ymag", 0.0);
  const double znear = number_member(o, "znear", -1.0);
  const double zfar = number_member(o, "zfar", 0.0);
  if (!(std::isfinite(xmag) && xmag != 0.0 && std::isfinite(ymag) && ymag != 0.0)) {
    ctx.fail(where,
             fmt::format("xmag and ymag must be finite and non-zero, got {} and {}", xmag, ymag));
  }
  if (!(std::isfinite(znear) && znear >= 0.0)) {
    ctx.fail(where, fmt::format("znear must be >= 0, got {}", znear));
  }
  if (!(std::isfinite(zfar) && zfar > znear)) {
    ctx.fail(where, fmt::format("zfar must be > znear, got {}", zfar));
  }
}

// Light colour (default white), every component finite and >= 0.
glm::dvec3 light_color(const Context& ctx, const json& l, const std::string& where) {
  const std::vector<double> color = numbers_member(l, "color");
  if (!member(l, "color")) return glm::dvec3(1.0);
  if (color.size() != 3) ctx.fail(where, "color must have 3 components");
  for (double c : color) {
    if (!(std::isfinite(c) && c >= 0.0)) ctx.fail(where, "color must be finite and >= 0");
  }
  return {color[0], color[1], color[2]};
}

// The light in its node's frame, validated; position and direction are set by place_light().
PunctualLight convert_light(const Context& ctx, const json& l, const std::string& where) {
  PunctualLight out;
  const std::string type = string_member(l, "type");
  out.kind = type == "spot"          ? PunctualLight::Kind::Spot
             : type == "directional" ? PunctualLight::Kind::Directional
                                     : PunctualLight::Kind::Point;
  const double intensity = number_member(l, "intensity", 1.0);
  if (!(std::isfinite(intensity) && intensity >= 0.0)) {
    ctx.fail(where, fmt::format("intensity must be finite and >= 0, got {}", intensity));
  }
  out.intensity = glm::vec3(light_color(ctx, l, where) * intensity);
  if (!std::isfinite(out.intensity.x + out.intensity.y + out.intensity.z)) {
    ctx.fail(where, "color * intensity overflows");
  }
  const double range = number_member(l, "range", 0.0);
  if (!(std::isfinite(range) && range >= 0.0)) ctx.fail(where, "range must be > 0");
  if (range > 0.0) ctx.warn("the range of KHR_lights_punctual lights is ignored");
  if (out.kind == PunctualLight::Kind::Spot) {
    const json* spot_ptr = member(l, "spot");
    const json& spot = spot_ptr ? *spot_ptr : json::object();
    const double inner = number_member(spot, "innerConeAngle", 0.0);
    const double outer = number_member(spot, "outerConeAngle", kPi / 4.0);
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
  const json& c = ctx.array("cameras")[camera];
  const std::string where = element("cameras", camera);
  ctx.use("cameras", camera);
  const std::string type = string_member(c, "type");
  const json* params = member(c, type.c_str());
  if ((type != "perspective" && type != "orthographic") || !params)
    ctx.fail(where, "type must be perspective or orthographic, with its object");
  const std::optional<glm::mat4> frame = camera_frame_of(world);
  if (!frame) ctx.fail(element("nodes", node), "the camera's node transform is singular");
  Camera out;
  const std::string name = string_member(c, "name");
  out.name = !name.empty() ? name : "camera" + std::to_string(camera);
  out.camera_to_world = *frame;
  const std::string pw = where + "." + type;
  if (type == "orthographic") {
    validate_orthographic(ctx, *params, pw);
    out.orthographic = true;
    out.xmag = float(std::abs(number_member(*params, "xmag", 1.0)));
    out.ymag = float(std::abs(number_member(*params, "ymag", 1.0)));
    out.aspect = out.xmag / out.ymag;
    out.znear = float(number_member(*params, "znear", 0.0));
    out.zfar = float(number_member(*params, "zfar", 0.0));
    return out;
  }
  validate_perspective(ctx, *params, pw);
  out.yfov = float(number_member(*params, "yfov", 0.0));
  if (const double aspect = number_member(*params, "aspectRatio", 0.0); aspect != 0.0)
    out.aspect = float(aspect);
  out.znear = float(number_member(*params, "znear", 0.0));
  if (const double zfar = number_member(*params, "zfar", 0.0); zfar != 0.0) out.zfar = float(zfar);
  return out;
}

std::optional<PunctualLight> place_light(const Context& ctx, std::size_t light, std::size_t node,
                                         const glm::dmat4& world) {
  const json& l = punctual_lights(ctx)[light];
  const std::string where = "extensions.KHR_lights_punctual.lights[" + std::to_string(light) + "]";
  const std::string type = string_member(l, "type");
  if (type != "point" && type != "spot" && type != "directional") {
    ctx.fail(where, "unknown light type '" + type + "'");
  }
  PunctualLight out = convert_light(ctx, l, where);
  const std::string name = string_member(l, "name");
  out.name = !name.empty() ? name : "light" + std::to_string(light);
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
