#include "apps/render_parts.h"

#include "apps/options.h"
#include "core/util/error.h"
#include "irad/parts.h"

#include <CLI/CLI.hpp>

namespace irad::apps {

void add_part_options(CLI::App& cmd, PartArgs& args) {
  args.command = &cmd;
  cmd.add_option("--path-range", args.path_range,
                 "raster, rt-vpl: render only paths A..B-1 of the N-path walk, A:B, or auto "
                 "(this Slurm array task's share), into a part for irad merge");
  cmd.add_option("--spp-range", args.spp_range,
                 "pt: render only samples A..B-1 of every pixel's S, A:B or auto, into a part "
                 "for irad merge");
}

bool is_part(const PartArgs& args) {
  return !args.path_range.empty() || !args.spp_range.empty();
}

void apply_part_ranges(const PartArgs& args, RenderRequest& request) {
  if (!args.path_range.empty()) {
    WalkOptions& walk = request.render.walk;
    if (request.render.auto_paths)
      throw Error("", "--path-range",
                  "needs --paths N: the parts must share one walk (auto chooses N per scene)");
    std::tie(walk.first_path, walk.end_path) =
        parse_part_range(args.path_range, walk.paths, "--path-range");
  }
  if (!args.spp_range.empty()) {
    PathTracerOptions& pt = request.render.pt;
    std::tie(pt.first_sample, pt.end_sample) =
        parse_part_range(args.spp_range, pt.spp, "--spp-range");
  }
}

ExrAttributes part_header(const PartArgs& args, const RenderRequest& request,
                          const RenderResult& result) {
  // What does not change the image: outputs, reports, threads (deterministic at any count),
  // the PNG tone map, the load limits (they only refuse), and the range itself.
  static const std::vector<std::string> ignored = {
      "--output",     "--stats",    "--quiet",         "--threads",       "--partial",
      "--exposure",   "--tonemap",  "--max-triangles", "--max-file-size", "--max-texture-size",
      "--path-range", "--spp-range"};
  PartInfo part;
  const bool paths = !args.path_range.empty();
  part.kind = paths ? "paths" : "spp";
  part.total = paths ? request.render.walk.paths : request.render.pt.spp;
  part.first = paths ? request.render.walk.first_path : request.render.pt.first_sample;
  part.end = paths ? request.render.walk.end_path : request.render.pt.end_sample;
  part.scene_file = request.scene_path;
  part.scene_hash = file_hash(request.scene_path);
  part.options = image_options(*args.command, ignored);
  if (!result.gl.empty()) part.options += ";gl-renderer=" + result.gl;
  part.version = irad_version();
  return part_attributes(part);
}

} // namespace irad::apps
