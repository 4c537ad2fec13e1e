#pragma once
// A clear sky and its sun: the model of Preetham, Shirley and Smits, "A Practical Analytic Model
// for Daylight" (SIGGRAPH 1999), from the paper's published coefficients.
//
// Sky: luminance and chromaticity each follow Perez's distribution
//   F(theta, gamma) = (1 + A e^(B / cos theta)) (1 + C e^(D gamma) + E cos^2 gamma),
// theta the view direction's angle from the zenith, gamma its angle from the sun, with A..E
// linear in the turbidity T; Y(theta, gamma) = Y_z F(theta, gamma) / F(0, theta_s) and the same
// for the chromaticities x, y; Y_z, x_z, y_z are the paper's zenith values at sun zenith angle
// theta_s. xyY -> XYZ -> linear Rec. 709 (sRGB primaries, D65), negatives clamped to 0.
// The sun is not part of the sky radiance.
//
// Units: irad radiance = luminance (cd/m^2) / (1e5 / pi): a white Lambertian plane under
// 100 klux has radiance 1. Irradiance likewise: E_irad = pi E_lux / 1e5.
//
// Frame: +Y up; a direction's azimuth a is measured from +Z toward +X (0: +Z, the side glTF
// assets face; 90: +X), elevation e from the horizon.
//
// Below the horizon (directions with y < 0) the sky is black, and with the sun at or below the
// horizon (elevation <= 0) the whole sky is black: the model has no twilight. Callers decide
// what to do with such a sky (preetham_sun says there is no sun).
#include "core/image/image.h"
#include "core/scene/scene.h"

#include <glm/glm.hpp>
#include <optional>
#include <string>

namespace irad {

struct SkyOptions {
  float elevation_deg = 45; // the sun's elevation above the horizon
  float azimuth_deg = 0;    // the sun's azimuth (see Frame above)
  float turbidity = 3;      // 2: very clear, 3: clear, 6: hazy; the model's range is [1.7, 10]
};

// The sun's apparent angular radius, 0.2667 degrees, in radians.
inline constexpr float kSunAngularRadius = 0.2667f * 3.14159265f / 180.0f;

// "ELEVATION[,AZIMUTH[,TURBIDITY]]" (degrees, degrees, turbidity): elevation in [-90, 90],
// azimuth any finite number, turbidity in [1.7, 10]. Throws Error("", option, ...) naming the
// value at fault.
SkyOptions parse_sky(const std::string& text, const std::string& option);

// Unit direction toward the sun: (cos e sin a, sin e, cos e cos a).
glm::vec3 sun_direction(const SkyOptions& sky);

// Sky radiance (sun excluded) arriving from unit direction w (pointing toward the sky).
glm::vec3 preetham_radiance(const SkyOptions& sky, const glm::vec3& w);

// The sky as an equirectangular map of width x width / 2 texels (width even, >= 2), each texel
// the radiance toward its centre, in core/environment/environment.h's orientation; alpha 1. The
// lower half (the rows below the horizon) is black.
Image preetham_sky_map(const SkyOptions& sky, int width = 512);

// The sun as a directional light: direction = -sun_direction (travel, into the scene),
// intensity = its irradiance at normal incidence in irad units per Rec. 709 channel,
// angular_radius = kSunAngularRadius; nullopt when the sun is not above the horizon.
// Per channel E = 128 klux (luminous solar constant, taken as white) times the transmittance
// tau(lambda) = tau_Rayleigh tau_aerosol of the paper's appendix at lambda = 0.680, 0.550, 0.440
// micrometres for R, G, B. Ozone and water vapour absorption are left out.
std::optional<PunctualLight> preetham_sun(const SkyOptions& sky);

} // namespace irad
