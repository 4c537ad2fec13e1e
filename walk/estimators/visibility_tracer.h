#pragma once
// The raster's visibility by rays (core/lights/visibility_request.h, RasterOptions::visibility):
// for each record and pixel of a request, whether rt-vpl's term of that VPL at the G-buffer's
// surface point is nonzero (walk/estimators/vpl_gather.h vpl_terms: the same emission, cosine and
// clamp tests, the same shadow ray from the point toward the VPL over (epsilon, distance -
// epsilon), mirrored and directional VPLs by their own rays). The raster shades with its own maths
// and reads V alone from this, so that its image differs from rt-vpl's over the same VPLs only
// where the G-buffer's point differs from the primary ray's hit (interpolation, float rounding).
#include "core/lights/visibility_request.h"
#include "walk/rays/ray_scene.h"

namespace irad {

// Fills request.out. dmin: the clamp distance (the fraction times the scene's diagonal, as
// rt-vpl's); threads: 0 for every core. Each record's pixels of one row are one task, the
// records of a set traced kVplChunk at a time from each pixel (RayScene's packets).
void trace_visibility(const RayScene& rays, float dmin, const VisibilityRequest& request,
                      unsigned threads = 0);

} // namespace irad
