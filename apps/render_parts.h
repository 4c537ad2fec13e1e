#pragma once
// irad render --path-range / --spp-range: a part of a render for irad merge (lib/irad/parts.h,
// docs/cluster.md). The part's EXR header names the scene (hash), N or S, the range, the
// options that change the image and irad's version.
#include "core/image/image_io.h"
#include "irad/render.h"

#include <string>

namespace CLI {
class App;
}

namespace irad::apps {

struct PartArgs {
  std::string path_range; // "A:B" or "auto"; empty: the whole render
  std::string spp_range;
  const CLI::App* command = nullptr; // irad render's options, for the header
};

void add_part_options(CLI::App& cmd, PartArgs& args);
bool is_part(const PartArgs& args);
// Sets the request's walk or path-tracer range. Throws irad::Error naming the option for a
// range outside 0..N (0..S), an empty one, or auto outside a Slurm array.
void apply_part_ranges(const PartArgs& args, RenderRequest& request);
// The EXR header of the rendered part (the GL renderer joins the options: parts of another
// driver are not merged with these).
ExrAttributes part_header(const PartArgs& args, const RenderRequest& request,
                          const RenderResult& result);

} // namespace irad::apps
