#pragma once
// Jittered low-discrepancy sampling (seed section 5.1.1): every VPL pass of the raster looks
// through the pixel at a sub-pixel offset of its own, so the accumulation, which averages the
// passes, box-filters the image over the pixel footprint: geometric edges come out antialiased
// without multisampling. No GL here: the offsets and the moved projection.
//
// Offsets are in pixels of the full image, x to the right and y down (image rows): a pass with
// offset o shades, at pixel (px, py), the surface seen through (px + 1/2 + o.x, py + 1/2 + o.y).
#include "core/lights/vpl.h"

#include <glm/glm.hpp>

namespace irad {

// The 2D low-discrepancy point of particle i that places its passes in the pixel: the Kronecker
// (rank-1 lattice) sequence u_i = frac(1/2 + i (1/g, 1/g^2)), g = 1.3247... the plastic number
// (the root of g^3 = g + 1). Why this point (docs/ext/jitter_textures.md has the measurements):
//  * a function of the particle i, not of the pass: the VPLs that reach reflection j are the
//    particles i < n_j (core/sampling/particle_counts.h), a prefix of the sequence, and every
//    prefix of this sequence covers the square evenly, so each depth's passes are stratified over
//    the pixel on their own. The pass index interleaves the depths (path 0's VPLs, then path 1's,
//    ...), so a radical inverse of it hands each depth an irregular subset.
//  * not the walk's radical inverses: Phi_2(i), Phi_3(i) already place the particle on the light
//    (dimensions 0 and 1), and a jitter equal to them would tie the light sample to the sub-pixel
//    position (at an edge pixel one surface would be lit from one half of the light only). The
//    next free Halton dimensions (2 l_max + 2, 2 l_max + 3) have bases like 59 and 61, whose first
//    points lie on the diagonal (i/59, i/61): 2D jitter of the first ~60 paths degenerates to 1D.
//    The Kronecker sequence is uniformly distributed jointly with radical inverses (an
//    irrational rotation against a van der Corput sequence), and good in 2D from the first point.
glm::vec2 path_jitter_point(std::uint32_t path);

// The jitter amplitude of a VPL at reflection `depth`, in pixels: the offset is
// amplitude * (u_i - 1/2), uniform over a square of that side. Depth 0 (direct light) gets the
// full pixel footprint (1: the box filter of the reference); reflection j gets 2^-j (the .cpp
// has the measurements).
float jitter_amplitude(int depth);

// The offset of one VPL pass (pixels).
glm::vec2 vpl_jitter(const Vpl& vpl);

// Jitter with the batched passes (raster/passes/batched_passes.h): their deferred shading reads a
// G-buffer drawn through one projection, so a VPL is shaded at the centre of the cell of a
// kJitterGrid x kJitterGrid grid over the pixel that holds its offset (the offset rounded to the
// nearest centre), and a G-buffer is drawn once per cell that has VPLs. Direct light (depth 0,
// offsets over the whole pixel) is then stratified exactly like the 16x supersampled
// reference's samples; the first reflection (amplitude 1/2) uses the four middle centres,
// +-1/8 pixel; deeper reflections the pixel centre (stratum kJitterStrata: the image's own
// G-buffer). tests/test_jitter.cpp measures it against the per-VPL offsets.
inline constexpr int kJitterGrid = 4;
inline constexpr int kJitterStrata = kJitterGrid * kJitterGrid;
// The cell (0 .. kJitterStrata - 1, x + kJitterGrid y) that holds vpl_jitter(vpl), or
// kJitterStrata (the pixel centre) for reflection 2 and deeper.
int jitter_stratum(const Vpl& vpl);
// The centre of cell `stratum` (< kJitterStrata) as an offset (pixels).
glm::vec2 stratum_offset(int stratum);

// The s-th of `count` offsets (s < count) of the camera passes that are not VPL passes (visible
// emitters, the interleaved resolve's albedo): a Hammersley set ((s + 1/2)/count, Phi_2(s)) - 1/2
// over the whole pixel, so their average is the same box filter.
glm::vec2 camera_jitter(int s, int count);

// The projection moved so that pixel centres sample at `offset` (pixels) in an image of
// width x height: clip-space x, y translated by -2 o.x / W and +2 o.y / H (times w).
glm::mat4 jittered_projection(const glm::mat4& projection, glm::vec2 offset, int width, int height);

} // namespace irad
