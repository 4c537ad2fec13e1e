#pragma once
// The raster with explicit settings for the hard-case tests (tests/test_hard_cases.cpp,
// tests/test_two_rooms.cpp); interleave 1 is the reference (every VPL shades every pixel), 4 the
// default (interleaved sampling and a geometry-aware resolve).
#include "raster/raster_renderer.h"

namespace irad::test_support {

inline RasterOptions raster_options(int shadow_resolution, float clamp, int interleave) {
  RasterOptions o;
  o.shadow_resolution = shadow_resolution;
  o.clamp = clamp;
  o.interleave = interleave;
  return o;
}

// Both ends of interleaving, which the hard cases render each.
inline constexpr int interleaves[] = {1, 4};

} // namespace irad::test_support
