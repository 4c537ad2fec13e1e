// The bundled Cornell box end to end: loader, walk, raster, and the command line.
#include "core/camera/view.h"
#include "core/gltf/loader.h"
#include "core/image/image_io.h"
#include "raster/raster_renderer.h"
#include "tests/test_paths.h"
#include "walk/vpls/quasi_random_walk.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace irad {
namespace IRAD_UNITY_ID {

namespace fs = std::filesystem;
const fs::path cornell = fs::path(IRAD_SOURCE_DIR) / "data/cornell_box.gltf";

// Mean of a (2r+1)^2 window around the pixel where world point p projects.
glm::vec3 mean_around(const Image& image, const View& view, const glm::vec3& p, int r = 2) {
  const glm::vec4 clip = view.projection * view.view * glm::vec4(p, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  const int cx = static_cast<int>((ndc.x * 0.5f + 0.5f) * static_cast<float>(view.width));
  const int cy = static_cast<int>((0.5f - ndc.y * 0.5f) * static_cast<float>(view.height));
  glm::vec3 sum(0.0f);
  for (int y = cy - r; y <= cy + r; ++y)
    for (int x = cx - r; x <= cx + r; ++x) sum += glm::vec3(image.at(x, y));
  return sum / static_cast<float>((2 * r + 1) * (2 * r + 1));
}

float red_share(const glm::vec3& c) {
  return c.r / (c.r + c.g + c.b);
}

TEST(Cornell, FiniteAndTheFloorBleedsTheWallColours) {
  Log log([](const std::string&) {});
  const Scene scene = load_gltf(cornell, log);
  const RayScene rays(scene);
  const VplSet vpls = quasi_random_walk(scene, rays, {128, 64}, log);
  RasterRenderer raster(scene, RasterOptions{});
  const View view = make_view(scene.cameras.at(0), scene.bounds, 128, 128);
  const Image image = raster.render(view, vpls);
  EXPECT_EQ(image.non_finite_count(), 0u);
  // Floor points 4 cm from the red wall (x = 0.55 m) and from the green wall (x = 0), in front of
  // both blocks.
  const glm::vec3 near_red = mean_around(image, view, {0.51f, 0.0f, 0.05f});
  const glm::vec3 near_green = mean_around(image, view, {0.04f, 0.0f, 0.05f});
  std::printf("floor near red %.4f %.4f %.4f, near green %.4f %.4f %.4f\n", near_red.r, near_red.g,
              near_red.b, near_green.r, near_green.g, near_green.b);
  EXPECT_GT(red_share(near_red), red_share(near_green) + 0.02f);
  EXPECT_GT(near_green.g / near_green.r, near_red.g / near_red.r);
  // The light's own pixel shows its radiance (17, 12, 4), added once, plus the light that the
  // floor reflects onto it (its albedo is 0.78): a little above L_e, never twice it.
  const glm::vec3 light = mean_around(image, view, {0.278f, 0.5487f, 0.2795f}, 0);
  EXPECT_GT(light.r, 17.0f);
  EXPECT_LT(light.r, 17.5f);
  EXPECT_GT(light.g, 12.0f);
  EXPECT_LT(light.g, 12.5f);
}

// The raster's one-time stages in --stats, in the order they ran (`list`: "raster_setup", or
// "hierarchy_beside" for the hierarchy's build beside them).
std::vector<std::string> setup_stages(const nlohmann::json& stats,
                                      const char* list = "raster_setup") {
  std::vector<std::string> stages;
  for (const auto& stage : stats["seconds"][list]) {
    stages.push_back(stage[0]);
    EXPECT_GE(stage[1].get<double>(), 0.0) << stage[0];
  }
  return stages;
}

bool has(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

// Twice through a fresh hierarchy cache: the first run builds and writes the box's shadow
// hierarchy, the second reads it back and draws the same image. Drawn with shadow maps (at 48x32
// `auto` traces the box's shadows, and nothing would scan its walls).
TEST(Cornell, CommandLineWritesImagesAndStats) {
  const fs::path dir = fs::path(::testing::TempDir()) / "irad_cornell_cli";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto run = [&](const std::string& name) {
    const std::string cmd = "XDG_CACHE_HOME=" + (dir / "cache").string() + " " +
                            std::string(IRAD_BINARY) + " render " + cornell.string() + " -o " +
                            (dir / (name + ".exr")).string() + " -o " +
                            (dir / (name + ".png")).string() +
                            " --size 48x32 --paths 16 --visibility maps --quiet --stats " +
                            (dir / (name + ".json")).string();
    EXPECT_EQ(std::system(cmd.c_str()), 0);
    std::ifstream in(dir / (name + ".json"));
    return nlohmann::json::parse(in);
  };
  const nlohmann::json stats = run("c");
  const Image exr = read_exr(dir / "c.exr");
  EXPECT_EQ(exr.width(), 48);
  EXPECT_EQ(exr.height(), 32);
  EXPECT_EQ(exr.non_finite_count(), 0u);
  EXPECT_GT(fs::file_size(dir / "c.png"), 100u);
  for (const char* key : {"vpls", "paths", "rho_bar", "l_max", "size", "seconds"})
    EXPECT_TRUE(stats.contains(key)) << key;
  for (const char* key : {"load", "walk", "raster", "total", "statistics"})
    EXPECT_TRUE(stats["seconds"].contains(key)) << key;
  // The estimates --stats asks for (clamped_fraction) ran after the image, apart from its time.
  EXPECT_GE(stats["clamped_fraction"].get<double>(), 0.0);
  EXPECT_GT(stats["seconds"]["statistics"].get<double>(), 0.0);
  EXPECT_GE(stats["seconds"]["total"].get<double>(), stats["seconds"]["raster"].get<double>());
  EXPECT_EQ(stats["paths"], 16);
  EXPECT_EQ(stats["size"][0], 48);
  // The hierarchy was built beside the load and the walk (lib/render.cpp early_hierarchy); the
  // raster waited for what was left of it.
  const std::vector<std::string> setup = setup_stages(stats);
  ASSERT_FALSE(setup.empty());
  EXPECT_TRUE(has(setup, "hierarchy wait"));
  EXPECT_FALSE(has(setup, "hierarchy levels"));
  EXPECT_TRUE(has(setup, "hierarchy upload"));
  EXPECT_EQ(setup.back(), "planes scan"); // when the first shadow maps were drawn to shade
  const std::vector<std::string> built = setup_stages(stats, "hierarchy_beside");
  EXPECT_TRUE(has(built, "hierarchy levels"));
  EXPECT_TRUE(has(built, "hierarchy cache write"));
  EXPECT_EQ(stats["hierarchy_cache"]["outcome"], "written");
  // The planes scan's (walk/walls/wall_cache.h).
  EXPECT_EQ(stats["wall_cache"]["outcome"], "written");

  const nlohmann::json again = run("d");
  const std::vector<std::string> read = setup_stages(again, "hierarchy_beside");
  EXPECT_TRUE(has(read, "hierarchy cache read"));
  EXPECT_FALSE(has(read, "hierarchy levels"));
  EXPECT_EQ(again["hierarchy_cache"]["outcome"], "hit");
  EXPECT_EQ(again["wall_cache"]["outcome"], "hit");
  EXPECT_TRUE(read_exr(dir / "d.exr").pixels() == exr.pixels());
  fs::remove_all(dir);
}

} // namespace IRAD_UNITY_ID
} // namespace irad
