#include "core/scene/analytic_scenes.h"

#include "core/scene/scene_builder.h"
#include "core/util/error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

namespace irad {

namespace {

constexpr double kPi = std::numbers::pi;

void require_albedo(const char* builder, double albedo) {
  if (!(albedo >= 0.0 && albedo < 1.0))
    throw Error(builder, "albedo", fmt::format("must be in [0, 1), got {}", albedo));
}

// An indexed triangle mesh on the unit sphere.
struct UnitMesh {
  std::vector<glm::dvec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> faces;
};

// Regular icosahedron with vertices at the poles: +z (vertex 0), a ring of five at
// z = 1/sqrt(5), another at z = -1/sqrt(5) turned by 36 degrees, and -z (vertex 11).
// Faces are counter-clockwise seen from outside.
UnitMesh icosahedron() {
  UnitMesh m;
  const double z = 1.0 / std::sqrt(5.0), r = 2.0 / std::sqrt(5.0);
  m.vertices.push_back({0.0, 0.0, 1.0});
  for (int k = 0; k < 5; ++k) {
    const double a = 2.0 * kPi * k / 5.0;
    m.vertices.push_back({r * std::cos(a), r * std::sin(a), z});
  }
  for (int k = 0; k < 5; ++k) {
    const double a = 2.0 * kPi * k / 5.0 + kPi / 5.0;
    m.vertices.push_back({r * std::cos(a), r * std::sin(a), -z});
  }
  m.vertices.push_back({0.0, 0.0, -1.0});
  for (std::uint32_t k = 0; k < 5; ++k) {
    const std::uint32_t u0 = 1 + k, u1 = 1 + (k + 1) % 5;
    const std::uint32_t l0 = 6 + k, l1 = 6 + (k + 1) % 5;
    m.faces.push_back({0, u0, u1});
    m.faces.push_back({u0, l0, u1});
    m.faces.push_back({u1, l0, l1});
    m.faces.push_back({11, l1, l0});
  }
  return m;
}

// Splits every face into four, the edge midpoints pushed onto the unit sphere. Each edge's
// midpoint is made once, so neighbouring faces share it exactly (no cracks).
UnitMesh subdivide(const UnitMesh& in) {
  UnitMesh out;
  out.vertices = in.vertices;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
  const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
    const std::pair<std::uint32_t, std::uint32_t> key = std::minmax(a, b);
    const auto found = midpoints.find(key);
    if (found != midpoints.end()) return found->second;
    out.vertices.push_back(glm::normalize(out.vertices[a] + out.vertices[b]));
    const auto index = static_cast<std::uint32_t>(out.vertices.size() - 1);
    midpoints.emplace(key, index);
    return index;
  };
  for (const auto& [a, b, c] : in.faces) {
    const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    out.faces.push_back({a, ab, ca});
    out.faces.push_back({ab, b, bc});
    out.faces.push_back({ca, bc, c});
    out.faces.push_back({ab, bc, ca});
  }
  return out;
}

// Appends triangle (p0, p1, p2) with its own three vertices and flat normal, oriented so that
// its front (counter-clockwise) side faces the origin.
void add_inward_triangle(Scene& s, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2,
                         std::uint32_t material) {
  glm::dvec3 c = glm::cross(glm::dvec3(p1) - glm::dvec3(p0), glm::dvec3(p2) - glm::dvec3(p0));
  if (glm::dot(c, glm::dvec3(p0) + glm::dvec3(p1) + glm::dvec3(p2)) > 0.0) {
    std::swap(p1, p2);
    c = -c;
  }
  const glm::vec3 n(glm::normalize(c));
  const auto base = static_cast<std::uint32_t>(s.positions.size());
  for (const glm::vec3& p : {p0, p1, p2}) {
    s.positions.push_back(p);
    s.normals.push_back(n);
  }
  s.triangles.push_back({base, base + 1, base + 2});
  s.triangle_material.push_back(material);
}

// Area of triangle t in double precision from the stored (float) vertices.
double area(const Scene& s, std::size_t t) {
  const glm::uvec3& tri = s.triangles[t];
  const glm::dvec3 p0(s.positions[tri.x]);
  return 0.5 * glm::length(glm::cross(glm::dvec3(s.positions[tri.y]) - p0,
                                      glm::dvec3(s.positions[tri.z]) - p0));
}

} // namespace

AnalyticScene integrating_sphere(double radius, double albedo, int subdivisions,
                                 double patch_radiance, double patch_angle) {
  const char* const who = "integrating_sphere";
  require_positive(who, "radius", radius);
  require_albedo(who, albedo);
  if (subdivisions < 0 || subdivisions > kMaxSphereSubdivisions)
    throw Error(who, "subdivisions",
                fmt::format("must be in [0, {}], got {}", kMaxSphereSubdivisions, subdivisions));
  require_positive(who, "patch_radiance", patch_radiance);
  if (!(patch_angle > 0.0 && patch_angle < 0.5 * kPi))
    throw Error(who, "patch_angle", fmt::format("must be in (0, pi/2), got {}", patch_angle));

  UnitMesh mesh = icosahedron();
  for (int k = 0; k < subdivisions; ++k) mesh = subdivide(mesh);

  AnalyticScene out;
  Scene& s = out.scene;
  s.source = fmt::format("integrating sphere (radius {}, albedo {}, {} subdivisions, patch "
                         "radiance {}, patch angle {})",
                         radius, albedo, subdivisions, patch_radiance, patch_angle);
  const auto rho = glm::vec3(static_cast<float>(albedo));
  const std::uint32_t wall = add_material(s, rho);
  const std::uint32_t patch = add_material(s, rho, glm::vec3(static_cast<float>(patch_radiance)));
  s.materials[wall].name = "wall";
  s.materials[patch].name = "patch";
  const double cos_patch = std::cos(patch_angle);
  for (const auto& face : mesh.faces) {
    std::array<glm::vec3, 3> p;
    glm::dvec3 centroid(0.0);
    for (std::size_t i = 0; i < 3; ++i) {
      p[i] = glm::vec3(radius * mesh.vertices[face[i]]);
      centroid += mesh.vertices[face[i]];
    }
    const bool touches_pole = face[0] == 0 || face[1] == 0 || face[2] == 0;
    const bool in_cap = glm::normalize(centroid).z > cos_patch;
    add_inward_triangle(s, p[0], p[1], p[2], touches_pole || in_cap ? patch : wall);
  }
  finish(s);

  // Near the centre, a little off it (no pixel ray along a symmetry axis of the mesh).
  const auto r = static_cast<float>(radius);
  Camera camera = look_at(glm::vec3(0.013f, -0.021f, 0.1f) * r, glm::vec3(0.0f, 0.0f, -r),
                          glm::vec3(0.0f, 1.0f, 0.0f), 0.9f);
  camera.name = "inside";
  s.cameras.push_back(camera);
  out.expected_radiance = integrating_sphere_radiance(s);
  return out;
}

double integrating_sphere_radiance(const Scene& scene) {
  const std::string& who = scene.source;
  if (scene.has_textures()) throw Error(who, "", "the sphere's answer needs untextured materials");
  if (!scene.lights.empty()) throw Error(who, "", "the sphere's answer needs no punctual lights");
  double total_area = 0.0, power = 0.0;
  std::optional<glm::vec3> rho;
  for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
    const Material& m = scene.material_of(t);
    const glm::vec3 c = m.base_color;
    if (c.x != c.y || c.y != c.z || (rho && *rho != c))
      throw Error(who, m.name, "the sphere's answer needs one grey albedo for every triangle");
    rho = c;
    const double a = area(scene, t);
    total_area += a;
    const glm::dvec3 e(m.emission);
    power += (m.double_sided ? 2.0 : 1.0) * kPi * a * (e.x + e.y + e.z) / 3.0;
  }
  if (!(power > 0.0)) throw Error(who, "", "the sphere's answer needs an emitter");
  const double r = rho->x;
  if (!(r < 1.0)) throw Error(who, "", "the sphere's answer needs albedo < 1");
  return r * power / (kPi * total_area * (1.0 - r));
}

AnalyticScene furnace_box(double size, double albedo, double emission) {
  const char* const who = "furnace_box";
  require_positive(who, "size", size);
  require_albedo(who, albedo);
  require_positive(who, "emission", emission);
  AnalyticScene out;
  Scene& s = out.scene;
  s.source = fmt::format("furnace box (size {}, albedo {}, emission {})", size, albedo, emission);
  const std::uint32_t wall = add_material(s, glm::vec3(static_cast<float>(albedo)),
                                          glm::vec3(static_cast<float>(emission)));
  s.materials[wall].name = "wall";
  const auto a = static_cast<float>(size);
  // Inward-facing walls (counter-clockwise seen from inside).
  add_quad(s, {0, 0, 0}, {0, 0, a}, {a, 0, a}, {a, 0, 0}, wall); // y = 0, normal +y
  add_quad(s, {0, a, 0}, {a, a, 0}, {a, a, a}, {0, a, a}, wall); // y = a, normal -y
  add_quad(s, {0, 0, 0}, {a, 0, 0}, {a, a, 0}, {0, a, 0}, wall); // z = 0, normal +z
  add_quad(s, {0, 0, a}, {0, a, a}, {a, a, a}, {a, 0, a}, wall); // z = a, normal -z
  add_quad(s, {0, 0, 0}, {0, a, 0}, {0, a, a}, {0, 0, a}, wall); // x = 0, normal +x
  add_quad(s, {a, 0, 0}, {a, 0, a}, {a, a, a}, {a, a, 0}, wall); // x = a, normal -x
  finish(s);
  // As in tests/test_references.cpp PathTracer.FurnaceBox: off-centre, so that no pixel centre
  // lands exactly on a seam of two walls.
  Camera camera = look_at(glm::vec3(0.47f, 0.53f, 0.95f) * a, glm::vec3(0.5f, 0.5f, 0.0f) * a,
                          glm::vec3(0.0f, 1.0f, 0.0f), 1.2f);
  camera.name = "inside";
  s.cameras.push_back(camera);
  out.expected_radiance = emission / (1.0 - albedo);
  return out;
}

AnalyticScene square_light(const SquareLight& light) {
  const char* const who = "square_light";
  require_positive(who, "side", light.side);
  require_positive(who, "height", light.height);
  require_positive(who, "radiance", light.radiance);
  require_positive(who, "plane_side", light.plane_side);
  if (!(light.albedo >= 0.0 && light.albedo <= 1.0))
    throw Error(who, "albedo", fmt::format("must be in [0, 1], got {}", light.albedo));
  AnalyticScene out;
  out.scene = square_light_over_plane(
      static_cast<float>(light.side), static_cast<float>(light.height),
      static_cast<float>(light.radiance), static_cast<float>(light.plane_side),
      static_cast<float>(light.albedo));
  Scene& s = out.scene;
  s.source = fmt::format("square light over a plane (side {}, height {}, radiance {}, plane side "
                         "{}, albedo {})",
                         light.side, light.height, light.radiance, light.plane_side, light.albedo);
  s.materials[0].name = "plane";
  s.materials[1].name = "light";
  const auto h = static_cast<float>(light.height);
  Camera camera = look_at({0.0f, 0.0f, 0.5f * h}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 1.6f);
  camera.name = "below-light";
  s.cameras.push_back(camera);
  return out;
}

double square_light_radiance(const SquareLight& light, const glm::dvec3& x) {
  const double p = 0.5 * light.plane_side, l = 0.5 * light.side, h = light.height;
  if (std::abs(x.x) > p || std::abs(x.y) > p) return 0.0;
  const std::vector<glm::dvec3> polygon = {{-l, -l, h}, {-l, l, h}, {l, l, h}, {l, -l, h}};
  return light.albedo / kPi *
         polygon_irradiance(polygon, {x.x, x.y, 0.0}, {0.0, 0.0, 1.0}, light.radiance);
}

} // namespace irad
