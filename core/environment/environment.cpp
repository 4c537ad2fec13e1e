#include "core/environment/environment.h"

#include "core/sampling/cdf.h"
#include "core/util/error.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

namespace irad {

namespace {

constexpr double pi = std::numbers::pi;

void check_aspect(const Image& map, const std::string& source) {
  if (map.width() < 2 || map.width() != 2 * map.height())
    throw Error(source, "",
                fmt::format("an equirectangular map is twice as wide as high, got {}x{}",
                            map.width(), map.height()));
}

void check_texel(const glm::vec3& c, std::size_t x, std::size_t y, const std::string& source) {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(c[k]) || c[k] < 0.0f)
      throw Error(
          source, "",
          fmt::format("texel ({}, {}) is {}: radiance must be finite and >= 0", x, y, c[k]));
}

} // namespace

glm::vec2 Environment::map_coordinates(const glm::vec3& d) {
  const double u =
      0.5 + std::atan2(static_cast<double>(d.z), static_cast<double>(d.x)) / (2.0 * pi);
  // acos(y) as atan2(|(x, z)|, y): the same for unit d, exact near the poles, and the formula
  // the raster's GLSL uses (raster/glsl/environment_glsl.h; GLSL's acos is imprecise on llvmpipe).
  const double x = d.x, z = d.z;
  const double v = std::atan2(std::sqrt(x * x + z * z), static_cast<double>(d.y)) / pi;
  return {static_cast<float>(u), static_cast<float>(v)};
}

glm::vec3 Environment::map_direction(double u, double v) {
  const double phi = 2.0 * pi * (u - 0.5), theta = pi * v;
  const double s = std::sin(theta);
  return {static_cast<float>(s * std::cos(phi)), static_cast<float>(std::cos(theta)),
          static_cast<float>(s * std::sin(phi))};
}

Environment::Environment(Image map, float strength, float rotation, std::string source)
    : map_(std::move(map)), strength_(strength), rotation_(rotation),
      cos_rotation_(std::cos(rotation)), sin_rotation_(std::sin(rotation)),
      source_(std::move(source)) {
  check_aspect(map_, source_);
  const std::size_t w = static_cast<std::size_t>(map_.width());
  const std::size_t h = static_cast<std::size_t>(map_.height());
  luminance_.resize(w * h);
  column_cdf_.resize(w * h);
  row_cdf_.resize(h);
  double mean = 0.0, rows = 0.0;
  for (std::size_t i = 0; i < h; ++i) {
    const double omega = (2.0 * pi / static_cast<double>(w)) *
                         (std::cos(pi * static_cast<double>(i) / static_cast<double>(h)) -
                          std::cos(pi * static_cast<double>(i + 1) / static_cast<double>(h)));
    double row = 0.0;
    for (std::size_t j = 0; j < w; ++j) {
      const glm::vec3 texel(map_.at(static_cast<int>(j), static_cast<int>(i)));
      check_texel(texel, j, i, source_); // in row order, before anything uses it
      const glm::vec3 l = strength_ * texel;
      luminance_[i * w + j] = luminance(l);
      row += static_cast<double>(luminance_[i * w + j]) * omega;
      column_cdf_[i * w + j] = row;
      mean += static_cast<double>(l.x + l.y + l.z) / 3.0 * omega;
    }
    for (std::size_t j = 0; j < w; ++j)
      column_cdf_[i * w + j] = row > 0.0 ? column_cdf_[i * w + j] / row : 0.0;
    if (row > 0.0) column_cdf_[i * w + w - 1] = 1.0;
    rows += row;
    row_cdf_[i] = rows;
  }
  total_luminance_ = rows;
  mean_integral_ = mean;
  for (double& c : row_cdf_) c = rows > 0.0 ? c / rows : 0.0;
  if (rows > 0.0) row_cdf_.back() = 1.0;
  if (!(strength_ >= 0.0f) || !std::isfinite(strength_))
    throw Error(source_, "--env-strength", "must be a finite number >= 0");
}

Image Environment::uniform_map(const glm::vec3& radiance) {
  Image map(2, 1);
  map.at(0, 0) = map.at(1, 0) = glm::vec4(radiance, 1.0f);
  return map;
}

Environment Environment::uniform(const glm::vec3& radiance, std::string source) {
  return Environment(uniform_map(radiance), 1.0f, 0.0f, std::move(source));
}

glm::vec3 Environment::to_map(const glm::vec3& w) const {
  const float c = cos_rotation_, s = sin_rotation_;
  // R_y(-a): x' = c x - s z, z' = s x + c z (R_y(a) takes +Z toward +X: x' = c x + s z).
  return {c * w.x - s * w.z, w.y, s * w.x + c * w.z};
}

glm::vec3 Environment::to_world(const glm::vec3& d) const {
  const float c = cos_rotation_, s = sin_rotation_;
  return {c * d.x + s * d.z, d.y, -s * d.x + c * d.z};
}

std::size_t Environment::texel_of(const glm::vec3& d) const {
  const glm::vec2 uv = map_coordinates(d);
  const int w = map_.width(), h = map_.height();
  const int x = std::clamp(static_cast<int>(std::floor(uv.x * static_cast<float>(w))), 0, w - 1);
  const int y = std::clamp(static_cast<int>(std::floor(uv.y * static_cast<float>(h))), 0, h - 1);
  return static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
}

glm::vec3 Environment::radiance(const glm::vec3& w) const {
  const std::size_t t = texel_of(to_map(w));
  return strength_ * glm::vec3(map_.pixels()[t]);
}

double Environment::pdf(const glm::vec3& w) const {
  if (black()) return 0.0;
  return static_cast<double>(luminance_[texel_of(to_map(w))]) / total_luminance_;
}

EnvironmentSample Environment::sample(double u, double v) const {
  EnvironmentSample s;
  if (black()) return s;
  const std::size_t w = static_cast<std::size_t>(map_.width());
  const std::size_t h = static_cast<std::size_t>(map_.height());
  double u_rest = 0.0, v_rest = 0.0;
  const std::size_t i = pick_from_cdf(row_cdf_.data(), h, u, u_rest);
  const std::size_t j = pick_from_cdf(column_cdf_.data() + i * w, w, v, v_rest);
  // Uniform in solid angle within the texel: cos theta uniform between the row's edges, phi
  // uniform across the column.
  const double c0 = std::cos(pi * static_cast<double>(i) / static_cast<double>(h));
  const double c1 = std::cos(pi * static_cast<double>(i + 1) / static_cast<double>(h));
  const double cos_t = c0 + u_rest * (c1 - c0);
  const double theta = std::acos(std::clamp(cos_t, -1.0, 1.0));
  const double col = (static_cast<double>(j) + v_rest) / static_cast<double>(w);
  const glm::vec3 d = map_direction(col, theta / pi);
  s.direction = glm::normalize(to_world(d));
  const std::size_t t = i * w + j;
  s.radiance = strength_ * glm::vec3(map_.pixels()[t]);
  s.pdf = static_cast<double>(luminance_[t]) / total_luminance_;
  return s;
}

} // namespace irad
