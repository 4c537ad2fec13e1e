// The Preetham et al. 1999 clear sky (core/environment/sky.h): option parsing, and properties of
// daylight the model must show (not its own formulas again): a plausible zenith luminance, a sky
// brighter toward the sun and at the horizon, darkest about 90 degrees from the sun, bluer when
// clear; a sun that dims and reddens as it sinks; a map in core/environment/environment.h's
// orientation.
#include "core/environment/environment.h"
#include "core/environment/sky.h"
#include "core/util/error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using irad::SkyOptions;

namespace IRAD_UNITY_ID {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLuxPerIrad = 1e5 / kPi;       // irradiance: irad units -> lux
constexpr double kKcdPerIrad = 1e5 / kPi / 1e3; // radiance: irad units -> kcd/m^2

// Unit direction at altitude `alt` and azimuth `az` (degrees; the frame of core/environment/sky.h).
glm::vec3 direction(double alt, double az) {
  const double a = alt * kPi / 180.0, b = az * kPi / 180.0;
  return glm::vec3(glm::dvec3(std::cos(a) * std::sin(b), std::sin(a), std::cos(a) * std::cos(b)));
}

double sky_luminance(const SkyOptions& sky, double alt, double az) {
  return irad::luminance(irad::preetham_radiance(sky, direction(alt, az)));
}

// The what() of the irad::Error thrown by parse_sky, or "" when it does not throw.
std::string sky_error(const std::string& text) {
  try {
    irad::parse_sky(text, "--sky");
  } catch (const irad::Error& e) {
    return e.what();
  }
  return "";
}

// Illuminance (lux, per Rec. 709 channel and as luminance) on a horizontal plane under a map:
// sum over texels of L cos theta dOmega, the cos integrated exactly over each texel's rows:
// integral of cos theta sin theta dtheta = (sin^2 theta_1 - sin^2 theta_0) / 2.
glm::dvec3 horizontal_illuminance(const irad::Image& map) {
  glm::dvec3 e(0.0);
  for (int j = 0; j < map.height(); ++j) {
    const double t0 = kPi * j / map.height(), t1 = kPi * (j + 1) / map.height();
    const double s0 = std::sin(t0), s1 = std::sin(t1);
    const double weight = (2.0 * kPi / map.width()) * 0.5 * (s1 * s1 - s0 * s0);
    for (int i = 0; i < map.width(); ++i) e += glm::dvec3(glm::vec3(map.at(i, j))) * weight;
  }
  return e * kLuxPerIrad;
}


TEST(Sky, ParsesOneToThreeFields) {
  const SkyOptions a = irad::parse_sky("30", "--sky");
  EXPECT_EQ(a.elevation_deg, 30.0f);
  EXPECT_EQ(a.azimuth_deg, 0.0f);
  EXPECT_EQ(a.turbidity, 3.0f);
  const SkyOptions b = irad::parse_sky("10.5,-45", "--sky");
  EXPECT_EQ(b.elevation_deg, 10.5f);
  EXPECT_EQ(b.azimuth_deg, -45.0f);
  const SkyOptions c = irad::parse_sky("-90,720,1.7", "--sky");
  EXPECT_EQ(c.elevation_deg, -90.0f);
  EXPECT_EQ(c.azimuth_deg, 720.0f);
  EXPECT_EQ(c.turbidity, 1.7f);
  EXPECT_EQ(irad::parse_sky("90,0,10", "--sky").turbidity, 10.0f);
}

TEST(Sky, RefusesBadOptionsNamingTheValue) {
  struct Case {
    std::string text, message;
  };
  const std::string syntax = "is not ELEVATION[,AZIMUTH[,TURBIDITY]]";
  const std::vector<Case> cases = {
      {"91", "--sky: elevation 91 is outside [-90, 90] degrees"},
      {"-91", "--sky: elevation -91 is outside [-90, 90] degrees"},
      {"45,0,1.5", "--sky: turbidity 1.5 is outside [1.7, 10]"},
      {"45,0,11", "--sky: turbidity 11 is outside [1.7, 10]"},
      {"high", "--sky: 'high' " + syntax},
      {"", "--sky: '' " + syntax},
      {"45,", "--sky: '45,' " + syntax},
      {"45,east", "--sky: '45,east' " + syntax},
      {" 45", "--sky: ' 45' " + syntax},
      {"nan", "--sky: 'nan' " + syntax},
      {"45,inf", "--sky: '45,inf' " + syntax},
      {"45,0,3,1", "--sky: '45,0,3,1' " + syntax},
  };
  for (const Case& c : cases) {
    const std::string what = sky_error(c.text);
    EXPECT_EQ(what.rfind(c.message, 0), 0u) << "'" << c.text << "' gave: " << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
}

TEST(Sky, SunDirectionFollowsTheFrame) {
  const auto near = [](glm::vec3 a, glm::vec3 b) { return glm::length(a - b) < 1e-6f; };
  EXPECT_TRUE(near(irad::sun_direction({0, 0, 3}), {0, 0, 1}));  // azimuth 0: +Z
  EXPECT_TRUE(near(irad::sun_direction({0, 90, 3}), {1, 0, 0})); // azimuth 90: +X
  EXPECT_TRUE(near(irad::sun_direction({90, 37, 3}), {0, 1, 0}));
  const glm::vec3 d = irad::sun_direction({30, 135, 3});
  EXPECT_NEAR(glm::length(d), 1.0f, 1e-6f);
  EXPECT_NEAR(d.y, 0.5f, 1e-6f);
}

// Preetham et al. plot zenith luminances of a few kcd/m^2 for a clear sky (T = 2) with the sun
// 30 degrees up; clear-sky measurements lie in the same range.
TEST(Sky, ZenithLuminanceIsPlausible) {
  const double zenith_kcd = sky_luminance({30, 0, 2}, 90, 0) * kKcdPerIrad;
  EXPECT_GT(zenith_kcd, 2.5);
  EXPECT_LT(zenith_kcd, 5.0);
  // A higher sun lights the zenith more.
  double previous = 0.0;
  for (float e : {5.0f, 15.0f, 30.0f, 45.0f, 60.0f}) {
    const double z = sky_luminance({e, 0, 3}, 90, 0);
    EXPECT_GT(z, previous) << "elevation " << e;
    previous = z;
  }
}

TEST(Sky, BrighterTowardTheSunThanOpposite) {
  for (float e : {10.0f, 30.0f, 60.0f}) {
    for (float az : {0.0f, 90.0f, 200.0f}) {
      const SkyOptions sky{e, az, 3};
      for (double alt : {10.0, 30.0})
        EXPECT_GT(sky_luminance(sky, alt, az), 1.2 * sky_luminance(sky, alt, az + 180.0))
            << "elevation " << e << " azimuth " << az << " altitude " << alt;
    }
  }
}

// Clear skies brighten toward the horizon: 90 degrees from the sun's azimuth, 5 degrees up is
// brighter than the zenith when the sun is low or moderate.
TEST(Sky, HorizonBrighterThanZenithAwayFromTheSun) {
  for (float t : {2.0f, 3.0f}) {
    const SkyOptions sky{30, 0, t};
    EXPECT_GT(sky_luminance(sky, 5, 90), sky_luminance(sky, 90, 0)) << "turbidity " << t;
  }
}

// The darkest part of a clear sky lies about 90 degrees from the sun.
TEST(Sky, DarkestAboutNinetyDegreesFromTheSun) {
  for (float e : {10.0f, 30.0f, 45.0f}) {
    const SkyOptions sky{e, 0, 3};
    double darkest = 1e30, gamma = 0.0;
    for (int alt = 1; alt < 90; ++alt) {
      for (int az = 0; az < 360; az += 2) {
        const double l = sky_luminance(sky, alt, az);
        if (l >= darkest) continue;
        darkest = l;
        gamma = std::acos(glm::dot(direction(alt, az), irad::sun_direction(sky))) * 180.0 / kPi;
      }
    }
    EXPECT_GT(gamma, 70.0) << "elevation " << e;
    EXPECT_LT(gamma, 110.0) << "elevation " << e;
  }
}

// The zenith is blue (B > G > R), and haze whitens it: B / R falls as turbidity rises.
TEST(Sky, ClearSkyIsBlueAndHazeWhitensIt) {
  double previous_ratio = 1e30;
  for (float t : {2.0f, 3.0f, 6.0f, 10.0f}) {
    const glm::vec3 z = irad::preetham_radiance({45, 0, t}, {0, 1, 0});
    EXPECT_GT(z.b, z.g) << "turbidity " << t;
    EXPECT_GT(z.g, z.r) << "turbidity " << t;
    EXPECT_LT(z.b / z.r, previous_ratio) << "turbidity " << t;
    previous_ratio = z.b / z.r;
  }
}

TEST(Sky, BlackBelowTheHorizonAndWithoutSun) {
  EXPECT_EQ(irad::preetham_radiance({45, 0, 3}, direction(-1, 30)), glm::vec3(0.0f));
  EXPECT_EQ(irad::preetham_radiance({0, 0, 3}, {0, 1, 0}), glm::vec3(0.0f));
  EXPECT_EQ(irad::preetham_radiance({-20, 0, 3}, direction(10, 0)), glm::vec3(0.0f));
  EXPECT_FALSE(irad::preetham_sun({0, 0, 3}).has_value());
  EXPECT_FALSE(irad::preetham_sun({-10, 0, 3}).has_value());
}

TEST(Sky, SunIsADirectionalLightTravellingFromTheSun) {
  const SkyOptions sky{40, 120, 3};
  const auto sun = irad::preetham_sun(sky);
  ASSERT_TRUE(sun.has_value());
  EXPECT_EQ(sun->kind, irad::PunctualLight::Kind::Directional);
  EXPECT_LT(glm::length(sun->direction + irad::sun_direction(sky)), 1e-6f);
  EXPECT_NEAR(sun->angular_radius, 0.2667 * kPi / 180.0, 1e-7);
}

// At the zenith in a clear sky (T = 3) direct normal illuminance is about 95 klux (80-110).
TEST(Sky, SunIrradianceAtZenithIsPlausible) {
  const auto sun = irad::preetham_sun({90, 0, 3});
  ASSERT_TRUE(sun.has_value());
  const double g_klux = sun->intensity.g * kLuxPerIrad / 1e3;
  EXPECT_GT(g_klux, 80.0);
  EXPECT_LT(g_klux, 110.0);
  // Clearer air lets more through.
  EXPECT_GT(irad::preetham_sun({90, 0, 2})->intensity.g, sun->intensity.g);
  EXPECT_LT(irad::preetham_sun({90, 0, 6})->intensity.g, sun->intensity.g);
}

TEST(Sky, LowerSunIsDimmerAndRedder) {
  glm::vec3 previous(1e30f);
  double previous_red_over_blue = 0.0;
  for (float e : {90.0f, 60.0f, 30.0f, 10.0f, 2.0f}) {
    const glm::vec3 e_sun = irad::preetham_sun({e, 0, 3})->intensity;
    for (int c = 0; c < 3; ++c) EXPECT_LT(e_sun[c], previous[c]) << "elevation " << e;
    const double red_over_blue = e_sun.r / e_sun.b;
    EXPECT_GT(red_over_blue, previous_red_over_blue) << "elevation " << e;
    previous = e_sun;
    previous_red_over_blue = red_over_blue;
  }
}

TEST(Sky, MapIsTwoToOneFiniteAndBlackBelowTheHorizon) {
  const irad::Image map = irad::preetham_sky_map({30, 0, 3}, 64);
  ASSERT_EQ(map.width(), 64);
  ASSERT_EQ(map.height(), 32);
  for (int j = 0; j < map.height(); ++j) {
    for (int i = 0; i < map.width(); ++i) {
      const glm::vec4 t = map.at(i, j);
      ASSERT_TRUE(std::isfinite(t.r) && std::isfinite(t.g) && std::isfinite(t.b));
      ASSERT_TRUE(t.r >= 0.0f && t.g >= 0.0f && t.b >= 0.0f);
      EXPECT_EQ(t.a, 1.0f);
      if (j >= map.height() / 2)
        EXPECT_EQ(glm::vec3(t), glm::vec3(0.0f)) << i << "," << j;
      else
        EXPECT_GT(irad::luminance(glm::vec3(t)), 0.0f) << i << "," << j;
    }
  }
  EXPECT_THROW(irad::preetham_sky_map({30, 0, 3}, 63), irad::Error);
  EXPECT_THROW(irad::preetham_sky_map({30, 0, 3}, 0), irad::Error);
}

// Texel (i, j) holds the radiance toward its centre: the zenith is row 0, and the brightest sky
// lies in the sun's column (azimuth 90 = +X: the map's centre; azimuth 0 = +Z: u = 3/4).
TEST(Sky, MapFollowsTheEnvironmentOrientation) {
  for (float az : {90.0f, 0.0f, -120.0f}) {
    const SkyOptions sky{20, az, 3};
    const irad::Image map = irad::preetham_sky_map(sky, 128);
    const glm::vec3 zenith_row = irad::preetham_radiance(sky, {0, 1, 0});
    EXPECT_NEAR(irad::luminance(glm::vec3(map.at(7, 0))), irad::luminance(zenith_row),
                0.02 * irad::luminance(zenith_row));
    int brightest = 0;
    float best = -1.0f;
    for (int i = 0; i < map.width(); ++i) {
      const float l = irad::luminance(glm::vec3(map.at(i, 28))); // about 11 degrees up
      if (l > best) best = l, brightest = i;
    }
    const glm::vec3 s = irad::sun_direction(sky);
    const double u = 0.5 + std::atan2(s.z, s.x) / (2.0 * kPi);
    EXPECT_NEAR((brightest + 0.5) / map.width(), u, 1.0 / map.width()) << "azimuth " << az;
  }
}

// Horizontal illuminance from the sky alone rises with the sun, stays within clear-sky bounds
// (a few to a few tens of klux), and is less than the sun's own on the plane once it is 30
// degrees up.
TEST(Sky, SkyIlluminanceRisesWithTheSun) {
  double previous = 0.0;
  for (float e : {10.0f, 30.0f, 60.0f, 90.0f}) {
    const SkyOptions sky{e, 0, 3};
    const double sky_lux =
        irad::luminance(glm::vec3(horizontal_illuminance(irad::preetham_sky_map(sky, 256))));
    EXPECT_GT(sky_lux, previous) << "elevation " << e;
    EXPECT_GT(sky_lux, 5e3) << "elevation " << e;
    EXPECT_LT(sky_lux, 50e3) << "elevation " << e;
    const double sun_lux = irad::luminance(irad::preetham_sun(sky)->intensity) * kLuxPerIrad *
                           std::sin(e * kPi / 180.0);
    if (e >= 30.0f) {
      EXPECT_LT(sky_lux, sun_lux) << "elevation " << e;
    }
    previous = sky_lux;
  }
}

} // namespace
