// Which lights a scene is rendered with (core/environment/lighting.h): the default white
// environment for unlit scenes (one warning), --env none, one environment at a time, the sky's sun,
// the summary
// --stats writes.
#include "core/environment/lighting.h"
#include "core/environment/sky.h"
#include "core/scene/scene_builder.h"
#include "core/util/error.h"

#include <cmath>
#include <gtest/gtest.h>
#include <string>
#include <vector>

namespace irad {
namespace IRAD_UNITY_ID {

Scene plane(bool emissive) {
  Scene s;
  s.source = "plane.gltf";
  const std::uint32_t m = add_material(s, glm::vec3(0.5f), glm::vec3(emissive ? 1.0f : 0.0f));
  add_quad(s, {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, m);
  finish(s);
  return s;
}

struct Logged {
  std::vector<std::string> lines;
  Log log{[this](const std::string& l) { lines.push_back(l); }};
};

TEST(Lighting, UnlitSceneGetsTheWhiteEnvironmentWithOneWarning) {
  Scene s = plane(false);
  Logged l;
  light_scene(s, {}, l.log);
  ASSERT_TRUE(s.has_environment());
  EXPECT_EQ(s.environment->radiance({0, 1, 0}), glm::vec3(1.0f));
  EXPECT_EQ(s.environment->radiance({0.3f, -0.9f, 0.1f}), glm::vec3(1.0f));
  ASSERT_EQ(l.lines.size(), 1u);
  EXPECT_NE(l.lines[0].find("plane.gltf"), std::string::npos);
  EXPECT_NE(l.lines[0].find("white environment"), std::string::npos);
  EXPECT_EQ(summarize_lights(s).environment, "uniform 1,1,1 (default)");
}

TEST(Lighting, EnvNoneRefusesUnlitScenesAndAddsNothingToLitOnes) {
  Scene dark = plane(false);
  Logged l;
  LightingOptions none;
  none.env = "none";
  try {
    light_scene(dark, none, l.log);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("plane.gltf: --env none: no light", 0), 0u) << e.what();
  }
  Scene lit = plane(true);
  light_scene(lit, none, l.log);
  EXPECT_FALSE(lit.environment);
  light_scene(lit, {}, l.log); // lit scenes get no default environment either
  EXPECT_FALSE(lit.environment);
  EXPECT_TRUE(l.lines.empty());
}

TEST(Lighting, ColourStrengthRotationAndVisibility) {
  Scene s = plane(true);
  Logged l;
  LightingOptions o;
  o.env_color = glm::vec3(0.25f, 0.5f, 1.0f);
  o.strength = 2.0f;
  o.visible = false;
  light_scene(s, o, l.log);
  ASSERT_TRUE(s.has_environment());
  EXPECT_EQ(s.environment->radiance({1, 0, 0}), glm::vec3(0.5f, 1.0f, 2.0f));
  EXPECT_FALSE(s.environment->visible);
  const LightSummary sum = summarize_lights(s);
  EXPECT_EQ(sum.emissive_triangles, 2u);
  EXPECT_EQ(sum.emissive_materials, 1u);
  EXPECT_EQ(sum.environment, "uniform 0.25,0.5,1");
}

TEST(Lighting, TheSkyBringsItsSunWhichTurnsWithTheMap) {
  Logged l;
  LightingOptions o;
  o.sky = "30,90";
  Scene s = plane(false);
  light_scene(s, o, l.log);
  ASSERT_TRUE(s.has_environment());
  ASSERT_EQ(s.lights.size(), 1u);
  const PunctualLight& sun = s.lights[0];
  EXPECT_EQ(sun.kind, PunctualLight::Kind::Directional);
  EXPECT_GT(sun.angular_radius, 0.0f);
  // Azimuth 90: toward +X, 30 degrees up; the light travels the other way.
  const glm::vec3 to_sun = sun_direction(parse_sky("30,90", "--sky"));
  EXPECT_NEAR(glm::dot(-sun.direction, to_sun), 1.0f, 1e-6f);
  EXPECT_TRUE(l.lines.empty());
  const LightSummary sum = summarize_lights(s);
  EXPECT_EQ(sum.directional, 1u);
  EXPECT_EQ(sum.suns, 1u);

  // --env-rotate 90 turns the sun from +X to -Z (R_y(90) takes +X to -Z), with its map.
  o.rotate_degrees = 90.0f;
  Scene turned = plane(false);
  light_scene(turned, o, l.log);
  ASSERT_EQ(turned.lights.size(), 1u);
  const glm::vec3 turned_sun = -turned.lights[0].direction;
  EXPECT_NEAR(turned_sun.x, 0.0f, 1e-5f);
  EXPECT_NEAR(turned_sun.z, -to_sun.x, 1e-5f);
  EXPECT_NEAR(turned_sun.y, to_sun.y, 1e-5f);
  const glm::vec3 w = glm::normalize(glm::vec3(0.3f, 0.5f, 0.8f));
  const glm::vec3 w_turned(w.z, w.y, -w.x); // R_y(90) w
  EXPECT_EQ(turned.environment->radiance(w_turned), s.environment->radiance(w));
}

TEST(Lighting, SunBelowTheHorizonWarnsAndLeavesAnUnlitSceneWithoutLight) {
  Logged l;
  LightingOptions o;
  o.sky = "-10";
  Scene s = plane(false);
  EXPECT_THROW(light_scene(s, o, l.log), Error);
  ASSERT_EQ(l.lines.size(), 1u);
  EXPECT_NE(l.lines[0].find("horizon"), std::string::npos);
  Scene lit = plane(true);
  light_scene(lit, o, l.log); // its own light is enough
  EXPECT_TRUE(lit.lights.empty());
}

TEST(Lighting, OneEnvironmentAtATime) {
  Logged l;
  LightingOptions o;
  o.sky = "30";
  o.env_color = glm::vec3(1.0f);
  Scene s = plane(false);
  try {
    light_scene(s, o, l.log);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--sky"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--env-color"), std::string::npos) << e.what();
  }
}

} // namespace
} // namespace irad
