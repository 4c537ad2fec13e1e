// irad merge PART.exr... -o OUT.exr [-o OUT.png]: the parts of one render (irad render
// --path-range / --spp-range, lib/irad/parts.h) summed into the whole image. Parts of another
// scene, options, version or size, and overlapping or missing ranges, are refused with one line
// naming the file; nothing is written then.
#include "apps/commands.h"
#include "apps/options.h"
#include "core/image/image_io.h"
#include "core/util/error.h"
#include "irad/parts.h"

#include <cstdio>
#include <memory>

namespace irad::apps {

namespace {

struct MergeArgs {
  std::vector<std::string> parts;
  std::vector<std::string> outputs;
  float exposure = 0.0f;
  std::string tone_map = "clamp";
  bool quiet = false;
};

int run_merge(const MergeArgs& args) {
  for (const std::string& o : args.outputs) {
    image_format_of(o);
    require_writable(o, "-o");
  }
  const MergedImage merged = merge_parts(args.parts);
  // The whole range: the merged EXR is itself a part of 0..N (it merges alone, or with nothing).
  ExrAttributes header = part_attributes(merged.info);
  header["irad.merged.parts"] = std::to_string(args.parts.size());
  PngOptions png;
  png.exposure = args.exposure;
  png.tone_map = args.tone_map == "reinhard" ? ToneMap::Reinhard : ToneMap::Clamp;
  for (const std::string& o : args.outputs) {
    if (image_format_of(o) == ImageFormat::Exr)
      write_exr(o, merged.image, header);
    else
      write_image(o, merged.image, png);
  }
  if (!args.quiet)
    std::fprintf(stderr, "irad: merged %zu parts of %s (%s 0:%u), %dx%d\n", args.parts.size(),
                 merged.info.scene_file.c_str(), merged.info.kind.c_str(), merged.info.total,
                 merged.image.width(), merged.image.height());
  return 0;
}

} // namespace

void add_merge_command(CLI::App& app, Commands& commands) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* cmd =
      app.add_subcommand("merge", "Sum the parts of a render (--path-range, --spp-range)");
  cmd->add_option("parts", args->parts, "Part EXRs of irad render --path-range/--spp-range")
      ->required();
  cmd->add_option("-o,--output", args->outputs,
                  "Output image (.exr linear float, .png sRGB); may be given several times")
      ->required();
  cmd->add_option("--exposure", args->exposure, "PNG exposure in stops (EV)")
      ->capture_default_str();
  cmd->add_option("--tonemap", args->tone_map, "PNG tone map")
      ->check(CLI::IsMember({"clamp", "reinhard"}))
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", args->quiet, "No summary on stderr");
  cmd->callback([args, &commands] { commands.selected = [args] { return run_merge(*args); }; });
}

} // namespace irad::apps
