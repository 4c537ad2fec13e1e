#pragma once
// Real-time instant radiosity (design.md section 1, seed section 5.1.3): a ring of the N most
// recent path images. Each frame traces one new light path (its VPLs, capped at l_max
// reflections), renders them into that path's image, and replaces the oldest image; the frame
// shown is the sum of the ring plus the visible emitters. The sum is kept as a running sum
// (subtract the image leaving, add the one arriving) and recomputed exactly from the ring every
// `resum_every` frames, which bounds the float drift. For a static scene and camera the sum of all
// N path images is exactly the full instant radiosity image of the same VPLs.
// Public header: no GL types. Memory: N path images of W x H RGBA32F, and two more.
#include "core/camera/view.h"
#include "core/image/image.h"
#include "core/lights/vpl.h"
#include "core/scene/scene.h"
#include "raster/raster_renderer.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace irad {

struct RingOptions {
  std::uint32_t paths = 64; // N, the ring's length
  int width = 256, height = 256;
  RasterOptions raster;  // clamp, shadow resolution, backend (interleave is not used)
  int resum_every = 256; // frames between exact re-sums (0: never)
  std::size_t memory_limit = std::size_t{2} << 30; // bytes for the path images
};

class RingRenderer {
public:
  // Throws irad::Error when the ring would exceed its memory limit or GL fails.
  RingRenderer(const Scene& scene, const RingOptions& options);
  ~RingRenderer();
  RingRenderer(const RingRenderer&) = delete;
  RingRenderer& operator=(const RingRenderer&) = delete;

  // Renders one path's VPLs (seen from `view`) into slot path mod N, replacing what was there;
  // `lobes`: what its glossy VPLs index (Vpl::lobe). A glossy receiver's light in the slot is
  // that toward this view's camera until the slot is drawn again.
  void replace(std::uint32_t path, const std::vector<Vpl>& vpls, const View& view,
               const std::vector<VplLobe>& lobes = {});
  // The running sum plus the emitters and the background (raster/passes/background.h) seen from
  // `view` (alpha 1).
  Image frame(const View& view);
  // The sum recomputed from the ring (what the running sum should be).
  Image exact_sum();
  void resum();

  // Re-uploads what the scene's animation moved (after Animation::pose on the scene given to
  // the constructor); the path images already in the ring keep the geometry they were drawn with.
  void scene_changed();

  std::uint32_t slots() const;
  std::size_t passes() const; // VPL passes drawn so far
  // Of them, those drawn one VPL at a time (RasterTimings::single_passes).
  std::size_t single_passes() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace irad
