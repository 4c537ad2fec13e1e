// The analytic scenes of design.md section 3 (core/scene/analytic_scenes.h): their geometry and
// answers, the glTF round trip (core/gltf/writer.h), the path tracer against their answers, and the
// `irad scene` command end to end.
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/gltf/writer.h"
#include "core/image/image_io.h"
#include "core/scene/analytic_scenes.h"
#include "core/scene/scene_builder.h"
#include "core/util/error.h"
#include "keep_written_gltf.h"
#include "tests/test_paths.h"
#include "walk/estimators/path_tracer.h"
#include "walk/rays/ray_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>

namespace fs = std::filesystem;

namespace irad {
namespace IRAD_UNITY_ID {

constexpr double pi = std::numbers::pi;

// A fresh folder for the current test, removed with it.
class TempFolder {
public:
  TempFolder() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::path(::testing::TempDir()) / ("irad_analytic_" + std::string(info->name()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempFolder() { fs::remove_all(path_); }
  TempFolder(const TempFolder&) = delete;
  TempFolder& operator=(const TempFolder&) = delete;
  fs::path operator/(const std::string& name) const { return path_ / name; }

private:
  fs::path path_;
};

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

double mean_red(const Image& image) {
  double sum = 0.0;
  for (const glm::vec4& p : image.pixels()) sum += p.r;
  return sum / static_cast<double>(image.pixels().size());
}

double worst_relative(const Image& image, double expected) {
  double worst = 0.0;
  for (const glm::vec4& p : image.pixels())
    worst = std::max(worst, std::abs(p.r - expected) / expected);
  return worst;
}

double total_area(const Scene& s) {
  double a = 0.0;
  for (std::size_t t = 0; t < s.triangle_count(); ++t) a += triangle_area(s, t);
  return a;
}

// ---------------------------------------------------------------------------------------------
// Geometry and answers

// Subdivision 0 is the icosahedron (circumradius R, edge a = 4R / sqrt(10 + 2 sqrt 5), area
// 5 sqrt(3) a^2) and its patch the five faces around the pole: A_patch = A/4, so
// L = rho (pi A/4 L_e) / (pi A (1 - rho)) = rho L_e / (4 (1 - rho)), whatever the radius.
TEST(AnalyticScenes, IntegratingSphereTinyCaseByHand) {
  const double radius = 2.0, rho = 0.6, le = 3.0;
  const AnalyticScene a = integrating_sphere(radius, rho, 0, le);
  ASSERT_EQ(a.scene.triangle_count(), 20u);
  const double edge = 4.0 * radius / std::sqrt(10.0 + 2.0 * std::sqrt(5.0));
  EXPECT_NEAR(total_area(a.scene), 5.0 * std::sqrt(3.0) * edge * edge, 1e-5);
  int patch = 0;
  for (std::size_t t = 0; t < 20; ++t) patch += a.scene.material_of(t).emissive() ? 1 : 0;
  EXPECT_EQ(patch, 5);
  ASSERT_TRUE(a.expected_radiance);
  EXPECT_NEAR(*a.expected_radiance, rho * le / (4.0 * (1.0 - rho)), 1e-6); // 1.125
  EXPECT_NEAR(integrating_sphere_radiance(integrating_sphere(7.0, rho, 0, le).scene), 1.125, 1e-6);
}

// Every triangle faces the centre (counter-clockwise seen from it, flat unit normal), no edge is
// open (the enclosure is closed), and the tessellated area tends to 4 pi R^2.
TEST(AnalyticScenes, IntegratingSphereIsAClosedInwardPolyhedron) {
  double previous_area = 0.0;
  for (int k = 0; k <= 4; ++k) {
    const double radius = 3.0;
    const AnalyticScene a = integrating_sphere(radius, 0.5, k);
    const Scene& s = a.scene;
    ASSERT_EQ(s.triangle_count(), 20u << (2 * k));
    std::map<std::tuple<float, float, float, float, float, float>, int> edges;
    for (std::size_t t = 0; t < s.triangle_count(); ++t) {
      const glm::vec3 n = geometric_normal(s, t);
      ASSERT_GT(triangle_area(s, t), 0.0f);
      const glm::uvec3 tri = s.triangles[t];
      const glm::vec3 centroid = (s.positions[tri.x] + s.positions[tri.y] + s.positions[tri.z]);
      EXPECT_LT(glm::dot(n, centroid), 0.0f) << "triangle " << t << " faces outward";
      for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(glm::length(s.normals[tri[i]]), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::dot(s.normals[tri[i]], n), 1.0f, 1e-6f);
        glm::vec3 p = s.positions[tri[i]], q = s.positions[tri[(i + 1) % 3]];
        if (std::tie(q.x, q.y, q.z) < std::tie(p.x, p.y, p.z)) std::swap(p, q);
        ++edges[{p.x, p.y, p.z, q.x, q.y, q.z}];
      }
    }
    for (const auto& [edge, count] : edges) ASSERT_EQ(count, 2) << "open or non-manifold edge";
    const double area = total_area(s) / (4.0 * pi * radius * radius);
    EXPECT_GT(area, previous_area);
    EXPECT_LT(area, 1.0);
    previous_area = area;
    ASSERT_EQ(s.cameras.size(), 1u);
    EXPECT_LT(glm::length(s.cameras[0].position()), 0.2f * static_cast<float>(radius));
    EXPECT_NEAR(s.bounds.hi.z, radius, 1e-5);
    EXPECT_NEAR(s.bounds.lo.z, -radius, 1e-5);
  }
  EXPECT_GT(previous_area, 0.998); // 0.998805 at 4 subdivisions
}

TEST(AnalyticScenes, AnswersAreScaleInvariant) {
  const double sphere = *integrating_sphere(1.0, 0.5).expected_radiance;
  EXPECT_NEAR(*integrating_sphere(100.0, 0.5).expected_radiance, sphere, 1e-6 * sphere);
  EXPECT_EQ(*furnace_box(0.01, 0.25, 3.0).expected_radiance, 4.0);
  SquareLight small, large;
  large.side = 10.0 * small.side;
  large.height = 10.0 * small.height;
  large.plane_side = 10.0 * small.plane_side;
  EXPECT_NEAR(square_light_radiance(small, {0.3, 0.2, 0.0}),
              square_light_radiance(large, {3.0, 2.0, 0.0}), 1e-12);
  EXPECT_FALSE(square_light(small).expected_radiance);
  EXPECT_EQ(square_light_radiance(small, {3.5, 0.0, 0.0}), 0.0); // off the plane
}

TEST(AnalyticScenes, BuildersRejectBadInput) {
  EXPECT_THROW(integrating_sphere(0.0, 0.5), Error);
  EXPECT_THROW(integrating_sphere(1.0, 1.0), Error);
  EXPECT_THROW(integrating_sphere(1.0, -0.1), Error);
  EXPECT_THROW(integrating_sphere(1.0, NAN), Error);
  EXPECT_THROW(integrating_sphere(1.0, 0.5, -1), Error);
  EXPECT_THROW(integrating_sphere(1.0, 0.5, kMaxSphereSubdivisions + 1), Error);
  EXPECT_THROW(integrating_sphere(1.0, 0.5, 2, 0.0), Error);
  EXPECT_THROW(integrating_sphere(1.0, 0.5, 2, 1.0, 2.0), Error);
  EXPECT_THROW(furnace_box(-1.0, 0.5, 1.0), Error);
  EXPECT_THROW(furnace_box(1.0, 1.0, 1.0), Error);
  EXPECT_THROW(furnace_box(1.0, 0.5, 0.0), Error);
  EXPECT_THROW(furnace_box(INFINITY, 0.5, 1.0), Error);
  SquareLight bad;
  bad.height = 0.0;
  EXPECT_THROW(square_light(bad), Error);
  bad = SquareLight{};
  bad.albedo = 1.5;
  EXPECT_THROW(square_light(bad), Error);
  EXPECT_THROW(closed_box(1.0f, 0.5f, 2.0f, 1.0f), Error);
  // The sphere's formula refuses scenes it does not describe.
  Scene two_albedos = integrating_sphere(1.0, 0.5, 1).scene;
  two_albedos.materials[1].base_color = glm::vec3(0.4f);
  EXPECT_THROW(integrating_sphere_radiance(two_albedos), Error);
}

// ---------------------------------------------------------------------------------------------
// glTF round trip

// The scene as load_gltf returns it: triangles grouped by material (one primitive each).
void expect_same_scene(const Scene& original, const Scene& loaded) {
  ASSERT_EQ(loaded.materials.size(), original.materials.size());
  for (std::size_t i = 0; i < original.materials.size(); ++i) {
    const Material &a = original.materials[i], &b = loaded.materials[i];
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.base_color, a.base_color);
    EXPECT_EQ(b.emission, a.emission) << a.name; // exact, also through emissive_strength
    EXPECT_EQ(b.double_sided, a.double_sided);
  }
  std::vector<std::size_t> order(original.triangle_count());
  for (std::size_t t = 0; t < order.size(); ++t) order[t] = t;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
    return original.triangle_material[x] < original.triangle_material[y];
  });
  ASSERT_EQ(loaded.triangle_count(), original.triangle_count());
  for (std::size_t t = 0; t < order.size(); ++t) {
    const glm::uvec3 a = original.triangles[order[t]], b = loaded.triangles[t];
    ASSERT_EQ(loaded.triangle_material[t], original.triangle_material[order[t]]);
    for (int i = 0; i < 3; ++i) {
      ASSERT_EQ(loaded.positions[b[i]], original.positions[a[i]]) << "triangle " << t;
      ASSERT_LT(glm::length(loaded.normals[b[i]] - original.normals[a[i]]), 1e-6f);
    }
  }
  EXPECT_EQ(loaded.bounds.lo, original.bounds.lo);
  EXPECT_EQ(loaded.bounds.hi, original.bounds.hi);
  ASSERT_EQ(loaded.cameras.size(), original.cameras.size());
  for (std::size_t i = 0; i < original.cameras.size(); ++i) {
    const Camera &a = original.cameras[i], &b = loaded.cameras[i];
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.yfov, a.yfov);
    EXPECT_EQ(b.aspect, a.aspect);
    for (int c = 0; c < 4; ++c)
      EXPECT_LT(glm::length(b.camera_to_world[c] - a.camera_to_world[c]), 1e-6f);
    // Same near and far planes for any image.
    const View va = make_view(a, original.bounds, 64, 48), vb = make_view(b, loaded.bounds, 64, 48);
    EXPECT_FLOAT_EQ(vb.znear, va.znear);
    EXPECT_FLOAT_EQ(vb.zfar, va.zfar);
  }
  ASSERT_EQ(loaded.lights.size(), original.lights.size());
  for (std::size_t i = 0; i < original.lights.size(); ++i) {
    const PunctualLight &a = original.lights[i], &b = loaded.lights[i];
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.kind, a.kind);
    EXPECT_EQ(b.position, a.position);
    EXPECT_LT(glm::length(b.direction - a.direction), 1e-6f);
    EXPECT_LE(glm::length(b.intensity - a.intensity), 1e-6f * glm::length(a.intensity));
    EXPECT_EQ(b.inner_cone, a.inner_cone);
    EXPECT_EQ(b.outer_cone, a.outer_cone);
  }
}

// Writes the scene to FILE (a copy kept as KEEP_AS for the validator, keep_written_gltf.h) and
// loads it back, failing on any loader warning.
Scene round_trip(const Scene& scene, const fs::path& file, const std::string& keep_as) {
  write_gltf(scene, file);
  test::keep_written_gltf(file, keep_as);
  EXPECT_FALSE(fs::exists(file.string() + ".tmp"));
  Log log([](const std::string& w) { ADD_FAILURE() << "loader warning: " << w; });
  return load_gltf(file, log);
}

TEST(AnalyticScenes, GltfRoundTripOfTheAnalyticScenes) {
  const TempFolder dir;
  const std::pair<const char*, AnalyticScene> scenes[] = {
      {"integrating_sphere", integrating_sphere(2.5, 0.7, 3, 4.0)},
      {"furnace_box", furnace_box(3.0, 0.4, 0.5)},
      {"square_light", square_light(SquareLight{})}};
  for (const auto& [name, a] : scenes) {
    SCOPED_TRACE(a.scene.source);
    expect_same_scene(a.scene, round_trip(a.scene, dir / "scene.gltf",
                                          std::string("round_trip_") + name + ".gltf"));
  }
}

// Materials with emission above 1 (KHR_materials_emissive_strength), double-sided ones, several
// cameras with and without aspect ratio, point, spot and directional lights, a material without
// triangles.
TEST(AnalyticScenes, GltfRoundTripOfEverythingTheWriterWrites) {
  const TempFolder dir;
  Scene s = closed_box(2.0f, 0.5f, 0.5f, 7.25f);
  const std::uint32_t coloured = add_material(s, {0.9f, 0.2f, 0.1f}, {0.3f, 2.5f, 0.0f}, true);
  add_material(s, {0.1f, 0.2f, 0.3f}); // unused
  add_quad(s, {0.5f, 0.5f, 1.0f}, {0.7f, 0.5f, 1.0f}, {0.7f, 0.8f, 1.0f}, {0.5f, 0.8f, 1.0f},
           coloured);
  s.cameras.push_back(look_at({1.0f, 1.1f, 1.9f}, {1.0f, 0.9f, 0.0f}, {0, 1, 0}, 0.8f));
  Camera wide = look_at({0.2f, 1.8f, 0.3f}, {1.5f, 0.1f, 1.7f}, {0, 1, 0}, 1.3f);
  wide.name = "wide";
  wide.aspect = 1.5f;
  wide.znear = 0.01f;
  wide.zfar = 10.0f;
  s.cameras.push_back(wide);
  PunctualLight point;
  point.name = "bulb";
  point.position = {1.0f, 1.5f, 1.0f};
  point.intensity = {2.0f, 1.0f, 0.5f};
  PunctualLight spot;
  spot.name = "spot";
  spot.kind = PunctualLight::Kind::Spot;
  spot.position = {0.3f, 1.9f, 0.4f};
  spot.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.3f));
  spot.intensity = {0.0f, 0.0f, 0.0f};
  spot.inner_cone = 0.2f;
  spot.outer_cone = 0.6f;
  PunctualLight down = spot; // its frame needs the other helper axis
  down.name = "down";
  down.direction = {0.0f, -1.0f, 0.0f};
  down.intensity = {3.0f, 3.0f, 3.0f};
  PunctualLight sun; // directional: irradiance along its direction, the position is unused
  sun.name = "sun";
  sun.kind = PunctualLight::Kind::Directional;
  sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, 0.25f));
  sun.intensity = {4.0f, 3.5f, 3.0f};
  s.lights = {point, spot, down, sun};
  finish(s);
  const fs::path file = dir / "everything.gltf";
  expect_same_scene(s, round_trip(s, file, "round_trip_everything.gltf"));
  const std::string text = read_text(file);
  EXPECT_NE(text.find("KHR_materials_emissive_strength"), std::string::npos);
  EXPECT_NE(text.find("data:application/octet-stream;base64,"), std::string::npos);
}

TEST(AnalyticScenes, GltfWriterErrorsNameTheFile) {
  const TempFolder dir;
  const Scene s = furnace_box(1.0, 0.5, 1.0).scene;
  try {
    write_gltf(s, dir / "missing" / "x.gltf");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("x.gltf"), std::string::npos) << e.what();
  }
  fs::create_directories(dir / "folder.gltf");
  EXPECT_THROW(write_gltf(s, dir / "folder.gltf"), Error);
  EXPECT_FALSE(fs::exists(dir / "folder.gltf.tmp"));
  Scene bad = s;
  bad.positions[0].x = NAN;
  EXPECT_THROW(write_gltf(bad, dir / "nan.gltf"), Error);
  EXPECT_FALSE(fs::exists(dir / "nan.gltf"));
}

// ---------------------------------------------------------------------------------------------
// The path tracer against the answers

// Relative error of the image mean and relative RMS over the pixels, against a uniform answer.
struct Deviation {
  double mean, rms, worst;
};
Deviation deviation(const Image& image, double expected) {
  double sum = 0.0, sum_sq = 0.0;
  for (const glm::vec4& p : image.pixels()) {
    sum += p.r;
    sum_sq += (p.r / expected - 1.0) * (p.r / expected - 1.0);
  }
  const auto n = static_cast<double>(image.pixels().size());
  return {sum / n / expected - 1.0, std::sqrt(sum_sq / n), worst_relative(image, expected)};
}

// The camera sees the far wall only. Tessellation error there, at 4 subdivisions (radiosity with
// exact point-to-facet form factors, core/scene/analytic_scenes.h): the mean over the far wall is
// off by -1e-5, single points by -0.65 % .. +0.60 %. Measured at 256 spp, 24x24, over seeds 0..19:
// image mean -0.055 % +- 0.062 % (worst seed 0.17 %), pixel RMS 1.9 % (noise), worst pixel 10.6 %
// (a rare firefly; 23.6 % at 3 subdivisions). Seed 11: see the printed line. A wrong bounce weight
// or patch power moves the mean by whole percents (a 1 % error in rho moves L by 2 %), hence 0.5 %
// (8 sigma).
TEST(AnalyticScenes, PathTracerMatchesIntegratingSphere) {
  const AnalyticScene a = integrating_sphere(1.0, 0.5);
  const double expected = *a.expected_radiance; // 0.0165107
  const RayScene rays(a.scene);
  const View view = make_view(a.scene.cameras[0], a.scene.bounds, 24, 24);
  const Image image = path_trace(a.scene, rays, view, {256, 11, 0, 1000});
  const Deviation d = deviation(image, expected);
  std::printf("pt integrating sphere: expected %.6f, mean off by %+.5f, pixel RMS %.4f, worst "
              "pixel %.4f\n",
              expected, d.mean, d.rms, d.worst);
  EXPECT_LT(std::abs(d.mean), 0.005);
  EXPECT_LT(d.rms, 0.03);   // 1.9 % noise; a firefly of 25 % in one pixel adds 0.2 %
  EXPECT_LT(d.worst, 0.35); // no black, NaN or stray pixels
}

// Measured at 256 spp, 24x24, over seeds 0..19: image mean -0.008 % +- 0.084 % (worst seed
// 0.23 %), pixel RMS 2.7 %, worst pixel 12.6 %. No tessellation error: the box is exact.
TEST(AnalyticScenes, PathTracerMatchesFurnaceBox) {
  const AnalyticScene a = furnace_box(1.0, 0.6, 0.8);
  const double expected = *a.expected_radiance; // 2
  const RayScene rays(a.scene);
  const View view = make_view(a.scene.cameras[0], a.scene.bounds, 24, 24);
  const Image image = path_trace(a.scene, rays, view, {256, 5, 0, 1000});
  const Deviation d = deviation(image, expected);
  std::printf("pt furnace box: expected %.6f, mean off by %+.5f, pixel RMS %.4f, worst pixel "
              "%.4f\n",
              expected, d.mean, d.rms, d.worst);
  EXPECT_LT(std::abs(d.mean), 0.005);
  EXPECT_LT(d.rms, 0.04);
  EXPECT_LT(d.worst, 0.35);
}

// The square light's camera and square_light_radiance() together: per pixel, the point of the
// plane z = 0 the pixel centre's ray hits and Lambert's answer there.
TEST(AnalyticScenes, PathTracerMatchesSquareLight) {
  const SquareLight light{0.5, 0.8, 2.0, 4.0, 0.7};
  const AnalyticScene a = square_light(light);
  const RayScene rays(a.scene);
  const View view = make_view(a.scene.cameras[0], a.scene.bounds, 24, 24);
  const Image image = path_trace(a.scene, rays, view, {512, 3, 0, 1000});
  const glm::dmat4 inv = glm::inverse(glm::dmat4(view.projection) * glm::dmat4(view.view));
  double sum_sq = 0.0;
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) {
      const double nx = (x + 0.5) / view.width * 2.0 - 1.0;
      const double ny = 1.0 - (y + 0.5) / view.height * 2.0;
      const glm::dvec4 far = inv * glm::dvec4(nx, ny, 1.0, 1.0);
      const glm::dvec3 eye(view.eye);
      const glm::dvec3 d = glm::normalize(glm::dvec3(far) / far.w - eye);
      const double expected = square_light_radiance(light, eye + (-eye.z / d.z) * d);
      const double rel = image.at(x, y).r / expected - 1.0;
      sum_sq += rel * rel;
    }
  const double rel_rms = std::sqrt(sum_sq / (view.width * view.height));
  std::printf("pt square light: relative RMS %.5f\n", rel_rms);
  // Measured: 0.0100 at 512 spp (noise only; PathTracer.SquareLightOverPlaneMatchesLambert
  // shows it falling as 1/sqrt(spp)).
  EXPECT_LT(rel_rms, 0.025);
}

// ---------------------------------------------------------------------------------------------
// The command line

struct CliRun {
  int code;
  std::string out, err;
};

CliRun run(const TempFolder& dir, const std::string& args) {
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd =
      std::string(IRAD_BINARY) + " " + args + " > '" + out.string() + "' 2> '" + err.string() + "'";
  const int status = std::system(cmd.c_str());
  return {WEXITSTATUS(status), read_text(out), read_text(err)};
}

// The value after "expected_radiance " on stdout, or NaN.
double printed_answer(const std::string& out) {
  const std::string key = "expected_radiance ";
  const auto at = out.find(key);
  return at == std::string::npos ? NAN : std::atof(out.c_str() + at + key.size());
}

TEST(AnalyticScenes, SceneCommandWritesWhatRenderReads) {
  const TempFolder dir;
  const std::string gltf = (dir / "s.gltf").string(), exr = (dir / "s.exr").string();
  const std::string render =
      "render '" + gltf + "' -o '" + exr + "' --estimator pt --spp 32 --size 16x16 --quiet";
  struct Case {
    std::string args;
    double expected;
  };
  const Case cases[] = {{"integrating-sphere --subdivisions 3 --albedo 0.6 --scale 10",
                         *integrating_sphere(10.0, 0.6, 3).expected_radiance},
                        {"furnace-box --albedo 0.3 --radiance 1.4 --scale 0.01", 2.0},
                        {"square-light", NAN}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const CliRun scene = run(dir, "scene " + c.args + " -o '" + gltf + "'");
    ASSERT_EQ(scene.code, 0) << scene.err;
    EXPECT_EQ(scene.out.rfind("scene ", 0), 0u) << scene.out;
    if (std::isnan(c.expected)) {
      EXPECT_NE(scene.out.find("expected_radiance varies per pixel"), std::string::npos);
      EXPECT_NE(scene.out.find("Lambert"), std::string::npos);
    } else {
      EXPECT_NEAR(printed_answer(scene.out), c.expected, 1e-7 * c.expected) << scene.out;
    }
    const CliRun r = run(dir, render);
    ASSERT_EQ(r.code, 0) << r.err;
    const Image image = read_exr(exr);
    ASSERT_EQ(image.width(), 16);
    EXPECT_EQ(image.non_finite_count(), 0u);
    // 32 spp, 256 pixels: about 0.4 % noise on the mean.
    if (!std::isnan(c.expected)) {
      EXPECT_NEAR(mean_red(image) / c.expected, 1.0, 0.03);
    }
    fs::remove(exr);
  }
  // Scale invariance of the printed answer.
  const double at_1 = printed_answer(run(dir, "scene integrating-sphere -o '" + gltf + "'").out);
  const double at_1000 =
      printed_answer(run(dir, "scene integrating-sphere --scale 1000 -o '" + gltf + "'").out);
  EXPECT_NEAR(at_1000, at_1, 1e-6 * at_1);
}

TEST(AnalyticScenes, SceneCommandRejectsBadArguments) {
  const TempFolder dir;
  const std::string out = " -o '" + (dir / "x.gltf").string() + "'";
  for (const std::string& args :
       {"scene furnace-box --subdivisions 2" + out, "scene integrating-sphere --albedo 1" + out,
        "scene integrating-sphere --subdivisions 9" + out, "scene cube" + out,
        "scene square-light --scale 0" + out, "scene square-light --scale -2" + out,
        "scene furnace-box -o '" + (dir / "x.glb").string() + "'",
        "scene furnace-box -o '" + (dir / "nowhere" / "x.gltf").string() + "'"}) {
    const CliRun r = run(dir, args);
    EXPECT_EQ(r.code, 1) << args;
    EXPECT_EQ(r.err.rfind("irad: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_FALSE(fs::exists(dir / "x.gltf")) << args;
  }
}

} // namespace IRAD_UNITY_ID
} // namespace irad
