#pragma once
// Comparing an image against a reference: the metrics of core/image/image_metrics.h (RMSE, relMSE,
// mean ratio, ... per pixel or over KxK blocks) and the EXR files of core/image/image_io.h.
#include "core/image/image.h"
#include "core/image/image_io.h"
#include "core/image/image_metrics.h"

#include <string>

namespace irad {

// The metrics of EXR file `image` against EXR file `reference` (what `irad compare` prints).
// Throws irad::Error naming the file that cannot be read, both files when their sizes differ,
// or "block" when block < 1.
ImageMetrics compare_files(const std::string& image, const std::string& reference, int block = 1);

} // namespace irad
