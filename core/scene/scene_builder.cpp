#include "core/scene/scene_builder.h"

#include "core/util/error.h"

#include <cmath>
#include <fmt/format.h>
#include <string>

namespace irad {

namespace {

// Throws unless lo <= value <= hi.
void require_in(const char* builder, const char* name, double value, double lo, double hi) {
  if (!(value >= lo && value <= hi))
    throw Error(builder, name, fmt::format("must be in [{}, {}], got {}", lo, hi, value));
}

} // namespace

void require_positive(const char* builder, const char* name, double value) {
  if (!(value > 0.0 && std::isfinite(value)))
    throw Error(builder, name, fmt::format("must be a finite number > 0, got {}", value));
}

void add_quad(Scene& scene, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
              const glm::vec3& p3, std::uint32_t material) {
  const glm::vec3 c012 = glm::cross(p1 - p0, p2 - p0);
  const glm::vec3 c023 = glm::cross(p2 - p0, p3 - p0);
  if (!(glm::length(c012) > 0.0f && glm::length(c023) > 0.0f))
    throw Error("add_quad", "", "degenerate quad (a triangle of zero area)");
  const auto base = static_cast<std::uint32_t>(scene.positions.size());
  const glm::vec3 n = glm::normalize(c012);
  for (const glm::vec3& p : {p0, p1, p2, p3}) {
    scene.positions.push_back(p);
    scene.normals.push_back(n);
  }
  scene.triangles.push_back({base, base + 1, base + 2});
  scene.triangles.push_back({base, base + 2, base + 3});
  scene.triangle_material.push_back(material);
  scene.triangle_material.push_back(material);
}

std::uint32_t add_material(Scene& scene, const glm::vec3& albedo, const glm::vec3& emission,
                           bool double_sided) {
  Material m;
  m.name = "material" + std::to_string(scene.materials.size());
  m.base_color = albedo;
  m.emission = emission;
  m.double_sided = double_sided;
  scene.materials.push_back(m);
  return static_cast<std::uint32_t>(scene.materials.size() - 1);
}

Camera look_at(const glm::vec3& eye, const glm::vec3& target, const glm::vec3& up, float yfov) {
  const glm::vec3 to_eye = eye - target;
  if (!(glm::length(to_eye) > 0.0f)) throw Error("look_at", "", "eye and target coincide");
  const glm::vec3 back = glm::normalize(to_eye);
  const glm::vec3 side = glm::cross(up, back);
  if (!(glm::length(side) > 0.0f))
    throw Error("look_at", "up", "parallel to the view direction (or zero)");
  const glm::vec3 right = glm::normalize(side);
  const glm::vec3 true_up = glm::cross(back, right);
  Camera c;
  c.name = "test";
  c.camera_to_world =
      glm::mat4(glm::vec4(right, 0), glm::vec4(true_up, 0), glm::vec4(back, 0), glm::vec4(eye, 1));
  c.yfov = yfov;
  return c;
}

void finish(Scene& scene) {
  scene.bounds = Bounds{};
  for (const glm::vec3& p : scene.positions) scene.bounds.extend(p);
}

Scene square_light_over_plane(float side, float height, float radiance, float plane_side,
                              float albedo) {
  const char* const who = "square_light_over_plane";
  require_positive(who, "side", side);
  require_positive(who, "height", height);
  require_positive(who, "plane_side", plane_side);
  require_in(who, "radiance", radiance, 0.0, HUGE_VAL);
  require_in(who, "albedo", albedo, 0.0, 1.0);
  Scene s;
  s.source = "square_light_over_plane";
  const std::uint32_t floor = add_material(s, glm::vec3(albedo));
  const std::uint32_t light = add_material(s, glm::vec3(0.0f), glm::vec3(radiance));
  const float p = 0.5f * plane_side, l = 0.5f * side;
  add_quad(s, {-p, -p, 0}, {p, -p, 0}, {p, p, 0}, {-p, p, 0}, floor);
  // Facing down (-z): counter-clockwise seen from below.
  add_quad(s, {-l, -l, height}, {-l, l, height}, {l, l, height}, {l, -l, height}, light);
  finish(s);
  return s;
}

double polygon_irradiance(const std::vector<glm::dvec3>& polygon, const glm::dvec3& x,
                          const glm::dvec3& n, double radiance) {
  double sum = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const glm::dvec3 a = glm::normalize(polygon[i] - x);
    const glm::dvec3 b = glm::normalize(polygon[(i + 1) % polygon.size()] - x);
    const double angle = std::acos(glm::clamp(glm::dot(a, b), -1.0, 1.0));
    sum += angle * glm::dot(n, glm::normalize(glm::cross(a, b)));
  }
  return 0.5 * radiance * std::abs(sum);
}

Scene closed_box(float size, float albedo, float patch, float radiance) {
  const char* const who = "closed_box";
  require_positive(who, "size", size);
  require_in(who, "albedo", albedo, 0.0, 1.0);
  require_positive(who, "patch", patch);
  require_in(who, "patch", patch, 0.0, size);
  require_in(who, "radiance", radiance, 0.0, HUGE_VAL);
  Scene s;
  s.source = "closed_box";
  const std::uint32_t wall = add_material(s, glm::vec3(albedo));
  const std::uint32_t light = add_material(s, glm::vec3(albedo), glm::vec3(radiance));
  const float a = size;
  // Inward-facing walls (counter-clockwise seen from inside).
  add_quad(s, {0, 0, 0}, {0, 0, a}, {a, 0, a}, {a, 0, 0}, wall); // floor y = 0, normal +y
  add_quad(s, {0, a, 0}, {a, a, 0}, {a, a, a}, {0, a, a}, wall); // ceiling, normal -y
  add_quad(s, {0, 0, 0}, {a, 0, 0}, {a, a, 0}, {0, a, 0}, wall); // z = 0, normal +z
  add_quad(s, {0, 0, a}, {0, a, a}, {a, a, a}, {a, 0, a}, wall); // z = a, normal -z
  add_quad(s, {0, 0, 0}, {0, a, 0}, {0, a, a}, {0, 0, a}, wall); // x = 0, normal +x
  add_quad(s, {a, 0, 0}, {a, 0, a}, {a, a, a}, {a, a, 0}, wall); // x = a, normal -x
  const float lo = 0.5f * (a - patch), hi = 0.5f * (a + patch), y = a * 0.999f;
  add_quad(s, {lo, y, lo}, {hi, y, lo}, {hi, y, hi}, {lo, y, hi}, light); // facing -y
  finish(s);
  return s;
}

} // namespace irad

namespace irad {

namespace {

// Adds the midpoint vertex of (a, b) (interpolated attributes) and returns its index.
std::uint32_t midpoint(Scene& s, std::uint32_t a, std::uint32_t b) {
  s.positions.push_back(0.5f * (s.positions[a] + s.positions[b]));
  s.normals.push_back(glm::normalize(s.normals[a] + s.normals[b]));
  if (!s.uvs.empty()) s.uvs.push_back(0.5f * (s.uvs[a] + s.uvs[b]));
  return static_cast<std::uint32_t>(s.positions.size() - 1);
}

} // namespace

void subdivide(Scene& scene, int levels) {
  for (int l = 0; l < levels; ++l) {
    std::vector<glm::uvec3> triangles;
    std::vector<std::uint32_t> materials;
    triangles.reserve(4 * scene.triangles.size());
    materials.reserve(4 * scene.triangles.size());
    for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
      const glm::uvec3 v = scene.triangles[t];
      const std::uint32_t ab = midpoint(scene, v.x, v.y), bc = midpoint(scene, v.y, v.z),
                          ca = midpoint(scene, v.z, v.x);
      for (const glm::uvec3& child : {glm::uvec3(v.x, ab, ca), glm::uvec3(ab, v.y, bc),
                                      glm::uvec3(ca, bc, v.z), glm::uvec3(ab, bc, ca)}) {
        triangles.push_back(child);
        materials.push_back(scene.triangle_material[t]);
      }
    }
    scene.triangles = std::move(triangles);
    scene.triangle_material = std::move(materials);
  }
}

} // namespace irad
