#pragma once
// Accuracy metrics between a test image A and a reference image B (linear float, same size), and
// a false-colour picture of their relative error. Only R, G and B are compared; alpha is ignored.
//
// Non-finite pixels: a pixel whose R, G or B is NaN or +-Inf is counted per image and left out of
// every sum, together with the same pixel of the other image (so A and B are always summed over
// the same pixels).
//
// Blocks: with block size K > 1 both images are first averaged over KxK blocks (the partial blocks
// at the right and bottom edges over the pixels they contain, and only over the pixels finite in
// both images); the error metrics are then computed on the block means, one sample per block.
// Averaging removes zero-mean noise but keeps bias, so comparing K = 1 with K = 8, say, tells the
// two apart. K = 1 compares pixel by pixel.
#include "core/image/image.h"

#include <array>
#include <cstddef>
#include <string>

namespace irad {

// eps of relMSE: (a - b)^2 / (b^2 + eps) keeps black reference pixels from dominating.
inline constexpr double kRelMseEpsilon = 1e-2;
// eps of the per-pixel relative error of the diff image: |a - b| / (|b| + eps).
inline constexpr double kRelErrorEpsilon = 1e-2;

struct ImageMetrics {
  int block = 1;               // K
  std::size_t nonfinite_a = 0; // pixels of A with a NaN or Inf in R, G or B
  std::size_t nonfinite_b = 0; // the same for the reference B
  std::size_t pixels = 0;      // pixels finite in both images: the ones that entered the sums
  std::size_t samples = 0;     // compared values per channel: pixels (K = 1) or non-empty blocks
  std::array<double, 3> rmse_rgb{}; // sqrt(mean over samples of (a_c - b_c)^2), per channel
  double rmse = 0.0;                // sqrt(mean over samples and R, G, B of (a_c - b_c)^2)
  double relmse = 0.0; // mean over samples and R, G, B of (a_c - b_c)^2 / (b_c^2 + kRelMseEpsilon)
  // sum a_c / sum b_c over the used pixels (the same for every K). Plain IEEE division: a
  // reference summing to 0 gives +-inf, or nan when A sums to 0 too.
  std::array<double, 3> mean_ratio{};
  double max_abs_error = 0.0; // max over samples and R, G, B of |a_c - b_c|
};
// With no usable pixel (samples == 0) rmse, relmse, mean_ratio and max_abs_error are NaN.

// Throws irad::Error naming both files unless the images have the same size.
void require_same_size(const Image& image, const std::string& image_file, const Image& reference,
                       const std::string& reference_file);

// Metrics of `image` against `reference`. Throws irad::Error when the sizes differ or block < 1.
ImageMetrics compare_images(const Image& image, const Image& reference, int block = 1);

struct DiffOptions {
  double max_error = 0.2; // relative error shown as full red (0.2: 20 %); must be > 0
  int block = 1;          // K: the error of each block's means is painted over the whole block
};

// The display value (before sRGB encoding) of error ramp position t = e / max_error, clamped to
// [0, 1]: black at 0, blue at 1/4, green at 1/2, yellow at 3/4, red at 1 and above, linear in
// between.
std::array<float, 3> error_ramp_display(double t);

// A false-colour image of the relative error e = mean over R, G, B of |a - b| / (|b| + eps) (eps =
// kRelErrorEpsilon, a and b the block means when block > 1) through error_ramp_display, pixels
// non-finite in either image in magenta, alpha 1. The colours are stored as linear values (the
// sRGB decoding of the ramp's display values), so write_png with exposure 0 and the Clamp tone
// map reproduces the ramp exactly (up to 8-bit rounding). Throws irad::Error like compare_images
// and when max_error is not a positive finite number.
Image relative_error_image(const Image& image, const Image& reference, const DiffOptions& options);

} // namespace irad
