#pragma once
// irad::Image and NumPy arrays: float32, shape (height, width, channels), row 0 at the top
// (irad's own order, so an array equals the EXR the CLI writes, pixel for pixel).
#include "core/image/image.h"

#include <pybind11/numpy.h>

namespace irad::python {

using FloatArray = pybind11::array_t<float, pybind11::array::c_style>;

// The image's R, G, B (channels 3) or R, G, B, A (channels 4) as a new array.
FloatArray to_array(const Image& image, int channels);
// A float32 array of shape (h, w, 3) or (h, w, 4), h, w >= 1 (alpha 1 when absent). Anything
// else (another dtype, another shape) throws irad::Error naming `what`.
Image to_image(const pybind11::array& array, const char* what);

} // namespace irad::python
