// Preetham et al. 1999, "A Practical Analytic Model for Daylight": the sky's Perez distributions
// and zenith values (the paper's Section 3.2 and Appendix A.2), and the sun's transmittance
// (the paper's appendix on sunlight, Rayleigh and aerosol terms only).
#include "core/environment/sky.h"

#include "core/environment/environment.h"

#include "core/util/error.h"
#include "core/util/number_list.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

namespace irad {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;

// Perez distribution coefficients A..E.
struct Perez {
  double A, B, C, D, E;

  // F(theta, gamma) = (1 + A e^(B / cos theta)) (1 + C e^(D gamma) + E cos^2 gamma). cos theta
  // is kept above 1e-4: at the horizon e^(B / cos theta) -> 0 (B < 0 for every T >= 1.7).
  double operator()(double cos_theta, double gamma) const {
    const double c = std::max(cos_theta, 1e-4);
    const double cos_gamma = std::cos(gamma);
    return (1.0 + A * std::exp(B / c)) *
           (1.0 + C * std::exp(D * gamma) + E * cos_gamma * cos_gamma);
  }
};

// Appendix A.2, the distribution coefficients as linear functions of turbidity: each row
// {a, b} gives a T + b, for A, B, C, D, E in turn.
constexpr double kPerezY[5][2] = {
    {0.1787, -1.4630}, {-0.3554, 0.4275}, {-0.0227, 5.3251}, {0.1206, -2.5771}, {-0.0670, 0.3703}};
constexpr double kPerezX[5][2] = {{-0.0193, -0.2592},
                                  {-0.0665, 0.0008},
                                  {-0.0004, 0.2125},
                                  {-0.0641, -0.8989},
                                  {-0.0033, 0.0452}};
constexpr double kPerezYc[5][2] = {{-0.0167, -0.2608},
                                   {-0.0950, 0.0092},
                                   {-0.0079, 0.2102},
                                   {-0.0441, -1.6537},
                                   {-0.0109, 0.0529}};

// Appendix A.2, the zenith chromaticities: x_z = [T^2 T 1] M [theta_s^3 theta_s^2 theta_s 1]^T
// (theta_s in radians), M for x and for y.
constexpr double kZenithX[3][4] = {{0.00166, -0.00375, 0.00209, 0.0},
                                   {-0.02903, 0.06377, -0.03202, 0.00394},
                                   {0.11693, -0.21196, 0.06052, 0.25886}};
constexpr double kZenithY[3][4] = {{0.00275, -0.00610, 0.00317, 0.0},
                                   {-0.04214, 0.08970, -0.04153, 0.00516},
                                   {0.15346, -0.26756, 0.06670, 0.26688}};

Perez perez_of(const double (&table)[5][2], double T) {
  const auto c = [&](int i) { return table[i][0] * T + table[i][1]; };
  return {c(0), c(1), c(2), c(3), c(4)};
}

double zenith_chromaticity(const double (&m)[3][4], double T, double theta_s) {
  const double t[3] = {T * T, T, 1.0};
  const double s[4] = {theta_s * theta_s * theta_s, theta_s * theta_s, theta_s, 1.0};
  double sum = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) sum += t[i] * m[i][j] * s[j];
  return sum;
}

// Appendix A.2: Y_z = (4.0453 T - 4.9710) tan chi - 0.2155 T + 2.4192 in kcd/m^2, with
// chi = (4/9 - T/120) (pi - 2 theta_s).
double zenith_luminance_kcd(double T, double theta_s) {
  const double chi = (4.0 / 9.0 - T / 120.0) * (kPi - 2.0 * theta_s);
  return (4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192;
}

// Linear Rec. 709 from CIE xyY (IEC 61966-2-1's XYZ -> sRGB matrix), negatives clamped to 0.
glm::vec3 rgb_of_xyY(double x, double y, double Y) {
  if (!(y > 0.0) || !(Y > 0.0)) return glm::vec3(0.0f);
  const double X = x * Y / y;
  const double Z = (1.0 - x - y) * Y / y;
  const double r = 3.2404542 * X - 1.5371385 * Y - 0.4985314 * Z;
  const double g = -0.9692660 * X + 1.8760108 * Y + 0.0415560 * Z;
  const double b = 0.0556434 * X - 0.2040259 * Y + 1.0572252 * Z;
  return glm::vec3(glm::max(glm::dvec3(r, g, b), glm::dvec3(0.0)));
}

// irad radiance per kcd/m^2: 1000 pi / 1e5.
constexpr double kRadiancePerKcd = 1000.0 * kPi / 1e5;

// The sky of one SkyOptions: coefficients and zenith values divided by F(0, theta_s).
class PreethamSky {
public:
  explicit PreethamSky(const SkyOptions& sky) : sun_(sun_direction(sky)) {
    const double T = sky.turbidity;
    const double theta_s = (90.0 - double(sky.elevation_deg)) * kDegree;
    lit_ = sky.elevation_deg > 0.0f;
    Y_ = perez_of(kPerezY, T);
    x_ = perez_of(kPerezX, T);
    y_ = perez_of(kPerezYc, T);
    zenith_Y_ = kRadiancePerKcd * zenith_luminance_kcd(T, theta_s) / Y_(1.0, theta_s);
    zenith_x_ = zenith_chromaticity(kZenithX, T, theta_s) / x_(1.0, theta_s);
    zenith_y_ = zenith_chromaticity(kZenithY, T, theta_s) / y_(1.0, theta_s);
  }

  // Black below the horizon and when the sun is not up.
  glm::vec3 radiance(const glm::dvec3& w) const {
    if (!lit_ || w.y < 0.0) return glm::vec3(0.0f);
    const double gamma = std::acos(std::clamp(glm::dot(w, glm::dvec3(sun_)), -1.0, 1.0));
    return rgb_of_xyY(zenith_x_ * x_(w.y, gamma), zenith_y_ * y_(w.y, gamma),
                      zenith_Y_ * Y_(w.y, gamma));
  }

private:
  glm::vec3 sun_;
  bool lit_ = false;
  Perez Y_{}, x_{}, y_{};
  double zenith_Y_ = 0.0, zenith_x_ = 0.0, zenith_y_ = 0.0;
};

// Relative optical air mass at sun zenith angle theta_s (Kasten's formula, as in the paper's
// appendix): m = 1 / (cos theta_s + 0.15 (93.885 - theta_s in degrees)^-1.253).
double air_mass(double theta_s) {
  return 1.0 / (std::cos(theta_s) + 0.15 * std::pow(93.885 - theta_s / kDegree, -1.253));
}

// tau(lambda) = tau_R tau_a, lambda in micrometres: Rayleigh tau_R = exp(-0.008735 lambda^-4.08 m),
// aerosol (Angstrom) tau_a = exp(-beta lambda^-alpha m), alpha = 1.3, beta = 0.04608 T - 0.04586.
double transmittance(double lambda, double T, double m) {
  const double rayleigh = std::exp(-0.008735 * std::pow(lambda, -4.08) * m);
  const double beta = 0.04608 * T - 0.04586;
  const double aerosol = std::exp(-beta * std::pow(lambda, -1.3) * m);
  return rayleigh * aerosol;
}

} // namespace

SkyOptions parse_sky(const std::string& text, const std::string& option) {
  const auto values = parse_number_list(text, 1, 3);
  if (!values) {
    throw Error("", option,
                fmt::format("'{}' is not ELEVATION[,AZIMUTH[,TURBIDITY]] (one to three finite "
                            "numbers: degrees, degrees, turbidity)",
                            text));
  }
  const std::vector<double>& v = *values;
  if (v[0] < -90.0 || v[0] > 90.0)
    throw Error("", option, fmt::format("elevation {} is outside [-90, 90] degrees", v[0]));
  if (v.size() == 3 && (v[2] < 1.7 || v[2] > 10.0)) {
    throw Error("", option,
                fmt::format("turbidity {} is outside [1.7, 10], the model's range "
                            "(2: very clear, 3: clear, 6: hazy)",
                            v[2]));
  }
  SkyOptions sky;
  sky.elevation_deg = static_cast<float>(v[0]);
  if (v.size() >= 2) sky.azimuth_deg = static_cast<float>(v[1]);
  if (v.size() == 3) sky.turbidity = static_cast<float>(v[2]);
  return sky;
}

glm::vec3 sun_direction(const SkyOptions& sky) {
  const double e = double(sky.elevation_deg) * kDegree;
  const double a = double(sky.azimuth_deg) * kDegree;
  return glm::vec3(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
}

glm::vec3 preetham_radiance(const SkyOptions& sky, const glm::vec3& w) {
  return PreethamSky(sky).radiance(glm::dvec3(w));
}

Image preetham_sky_map(const SkyOptions& sky, int width) {
  if (width < 2 || width % 2 != 0)
    throw Error("", "sky map", fmt::format("width {} is not even and >= 2", width));
  const PreethamSky model(sky);
  Image map(width, width / 2);
  for (int j = 0; j < map.height(); ++j) {
    for (int i = 0; i < width; ++i) {
      const glm::dvec3 d(Environment::map_direction((i + 0.5) / width, (j + 0.5) / map.height()));
      map.at(i, j) = glm::vec4(model.radiance(d), 1.0f);
    }
  }
  return map;
}

std::optional<PunctualLight> preetham_sun(const SkyOptions& sky) {
  if (!(sky.elevation_deg > 0.0f)) return std::nullopt;
  const double theta_s = (90.0 - double(sky.elevation_deg)) * kDegree;
  const double m = air_mass(theta_s);
  constexpr double kSolarLux = 128e3; // the luminous solar constant, outside the atmosphere
  const double lambda[3] = {0.680, 0.550, 0.440};
  PunctualLight sun;
  sun.name = "sun";
  sun.kind = PunctualLight::Kind::Directional;
  sun.direction = -sun_direction(sky);
  for (int c = 0; c < 3; ++c)
    sun.intensity[c] =
        static_cast<float>(kPi * kSolarLux * transmittance(lambda[c], sky.turbidity, m) / 1e5);
  sun.angular_radius = kSunAngularRadius;
  return sun;
}

} // namespace irad
