#include "core/image/image_metrics.h"

#include "core/util/error.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <vector>

namespace irad {

namespace {

using Rgb = std::array<double, 3>;

bool finite_rgb(const glm::vec4& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

std::size_t count_nonfinite(const Image& image) {
  return static_cast<std::size_t>(std::count_if(image.pixels().begin(), image.pixels().end(),
                                                [](const glm::vec4& p) { return !finite_rgb(p); }));
}

std::string size_text(const Image& image) {
  return fmt::format("{}x{}", image.width(), image.height());
}

// Throws unless the sizes match and block >= 1.
void check_inputs(const Image& image, const Image& reference, int block) {
  if (image.width() != reference.width() || image.height() != reference.height())
    throw Error("", "",
                fmt::format("image sizes differ: {} against the reference's {}", size_text(image),
                            size_text(reference)));
  if (block < 1)
    throw Error("", "block", fmt::format("{} is not a block size (at least 1)", block));
}

// The sums of A and B over the pixels of one block that are finite in both images.
struct BlockSums {
  Rgb a{};
  Rgb b{};
  std::size_t count = 0;

  void add(const glm::vec4& pa, const glm::vec4& pb) {
    if (!finite_rgb(pa) || !finite_rgb(pb)) return;
    for (int c = 0; c < 3; ++c) {
      a[c] += pa[c];
      b[c] += pb[c];
    }
    ++count;
  }
};

// Calls f(bx, by, sums) for every KxK block (partial at the right and bottom edges) holding at
// least one pixel finite in both images, one row of blocks at a time: only that row's sums are
// kept, so K = 1 costs no copy of the images. The images have the same size.
template <class F>
void for_each_block(const Image& a, const Image& b, int k, F&& f) {
  k = std::min(k, std::max(a.width(), a.height())); // one block covers it all; no int overflow
  const int cols = (a.width() + k - 1) / k;
  std::vector<BlockSums> row(static_cast<std::size_t>(cols));
  for (int by = 0; by * k < a.height(); ++by) {
    std::fill(row.begin(), row.end(), BlockSums{});
    const int y_end = std::min(a.height(), (by + 1) * k);
    for (int y = by * k; y < y_end; ++y)
      for (int x = 0; x < a.width(); ++x) row[x / k].add(a.at(x, y), b.at(x, y));
    for (int bx = 0; bx < cols; ++bx)
      if (row[bx].count > 0) f(bx, by, row[bx]);
  }
}

// The error sums over samples (block means), and the plain pixel sums for the mean ratio.
struct ErrorSums {
  Rgb squared{};  // sum of (a_c - b_c)^2
  double rel = 0; // sum over channels of (a_c - b_c)^2 / (b_c^2 + eps)
  double max_abs = 0;
  Rgb sum_a{};
  Rgb sum_b{};
  std::size_t samples = 0;
  std::size_t pixels = 0;

  void add(const BlockSums& s) {
    const double n = static_cast<double>(s.count);
    for (int c = 0; c < 3; ++c) {
      const double b = s.b[c] / n;
      const double d = s.a[c] / n - b;
      squared[c] += d * d;
      rel += d * d / (b * b + kRelMseEpsilon);
      max_abs = std::max(max_abs, std::abs(d));
      sum_a[c] += s.a[c];
      sum_b[c] += s.b[c];
    }
    ++samples;
    pixels += s.count;
  }
};

ImageMetrics finish(const ErrorSums& s, int block) {
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  ImageMetrics m;
  m.block = block;
  m.samples = s.samples;
  m.pixels = s.pixels;
  const double n = static_cast<double>(s.samples);
  for (int c = 0; c < 3; ++c) {
    m.rmse_rgb[c] = s.samples > 0 ? std::sqrt(s.squared[c] / n) : nan;
    m.mean_ratio[c] = s.samples > 0 ? s.sum_a[c] / s.sum_b[c] : nan;
  }
  m.rmse = s.samples > 0 ? std::sqrt((s.squared[0] + s.squared[1] + s.squared[2]) / (3 * n)) : nan;
  m.relmse = s.samples > 0 ? s.rel / (3 * n) : nan;
  m.max_abs_error = s.samples > 0 ? s.max_abs : nan;
  return m;
}

// The sRGB decoding (inverse of linear_to_srgb) of a display value in [0, 1].
float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// e = mean over R, G, B of |a - b| / (|b| + eps) of one block's means.
double relative_error(const BlockSums& s) {
  const double n = static_cast<double>(s.count);
  double e = 0;
  for (int c = 0; c < 3; ++c)
    e += std::abs(s.a[c] - s.b[c]) / n / (std::abs(s.b[c]) / n + kRelErrorEpsilon);
  return e / 3;
}

glm::vec4 ramp_colour(double e, double max_error) {
  const std::array<float, 3> d = error_ramp_display(e / max_error);
  return {srgb_to_linear(d[0]), srgb_to_linear(d[1]), srgb_to_linear(d[2]), 1.0f};
}

void fill_block(Image& image, int bx, int by, int k, const glm::vec4& colour) {
  const int x_end = std::min(image.width(), (bx + 1) * k);
  const int y_end = std::min(image.height(), (by + 1) * k);
  for (int y = by * k; y < y_end; ++y)
    for (int x = bx * k; x < x_end; ++x) image.at(x, y) = colour;
}

} // namespace

void require_same_size(const Image& image, const std::string& image_file, const Image& reference,
                       const std::string& reference_file) {
  if (image.width() == reference.width() && image.height() == reference.height()) return;
  throw Error(image_file, "",
              fmt::format("size {} differs from the reference {} ({})", size_text(image),
                          reference_file, size_text(reference)));
}

ImageMetrics compare_images(const Image& image, const Image& reference, int block) {
  check_inputs(image, reference, block);
  ErrorSums sums;
  for_each_block(image, reference, block, [&sums](int, int, const BlockSums& s) { sums.add(s); });
  ImageMetrics m = finish(sums, block);
  m.nonfinite_a = count_nonfinite(image);
  m.nonfinite_b = count_nonfinite(reference);
  return m;
}

std::array<float, 3> error_ramp_display(double t) {
  static constexpr std::array<std::array<float, 3>, 5> stops = {
      {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}};
  if (!(t > 0)) return stops.front();
  if (t >= 1) return stops.back();
  const double s = t * 4;
  const std::size_t i = static_cast<std::size_t>(s);
  const float f = static_cast<float>(s - static_cast<double>(i));
  std::array<float, 3> out{};
  for (std::size_t c = 0; c < 3; ++c) out[c] = stops[i][c] + f * (stops[i + 1][c] - stops[i][c]);
  return out;
}

// Blocks are painted first (every pixel of a block with a usable pixel gets its colour); then
// every pixel non-finite in either image is overwritten with magenta. A block without a usable
// pixel consists of such pixels only, so every pixel is set.
Image relative_error_image(const Image& image, const Image& reference, const DiffOptions& options) {
  check_inputs(image, reference, options.block);
  if (!(options.max_error > 0) || !std::isfinite(options.max_error))
    throw Error("", "diff max", fmt::format("{} is not a positive number", options.max_error));
  Image out(image.width(), image.height());
  const int k = std::min(options.block, std::max(image.width(), image.height()));
  for_each_block(image, reference, k, [&](int bx, int by, const BlockSums& s) {
    fill_block(out, bx, by, k, ramp_colour(relative_error(s), options.max_error));
  });
  const glm::vec4 magenta(1.0f, 0.0f, 1.0f, 1.0f);
  for (std::size_t i = 0; i < out.pixels().size(); ++i)
    if (!finite_rgb(image.pixels()[i]) || !finite_rgb(reference.pixels()[i]))
      out.pixels()[i] = magenta;
  return out;
}

} // namespace irad
