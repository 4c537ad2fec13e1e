// The render's options by name (the command line's and Python's words for them) and the light
// budget's options (lib/irad/render.h).
#include "irad/render.h"

#include "core/util/error.h"

#include <string>

namespace irad {

Estimator parse_estimator(const std::string& name) {
  if (name == "raster") return Estimator::Raster;
  if (name == "rt-vpl") return Estimator::RtVpl;
  if (name == "pt") return Estimator::Pt;
  throw Error("", "--estimator", "'" + name + "' is not raster, rt-vpl or pt");
}

const char* estimator_name(Estimator estimator) {
  switch (estimator) {
  case Estimator::Raster:
    return "raster";
  case Estimator::RtVpl:
    return "rt-vpl";
  case Estimator::Pt:
    break;
  }
  return "pt";
}

bool set_edge_pixels(const std::string& name, RenderOptions& o) {
  if (name != "auto" && name != "traced" && name != "shaded" && name != "off") return false;
  o.auto_edges = name == "auto";
  o.raster.edge_pixels = name == "traced"   ? EdgePixelMode::Listed
                         : name == "shaded" ? EdgePixelMode::Shaded
                                            : EdgePixelMode::Off;
  return true;
}

const char* edge_mode_name(EdgePixelMode mode) {
  return mode == EdgePixelMode::Listed   ? "traced"
         : mode == EdgePixelMode::Shaded ? "shaded"
                                         : "off";
}

RenderOptions with_light_budget(RenderOptions o) {
  o.auto_paths = o.auto_clusters = o.auto_edges = true;
  o.raster.interleave = 0;
  return o;
}

} // namespace irad
