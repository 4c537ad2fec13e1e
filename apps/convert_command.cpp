// irad convert IN.exr -o OUT.png|OUT.exr [--exposure EV] [--tonemap clamp|reinhard]: re-encodes
// a linear EXR (for example a reference rendered earlier) with the same PNG pipeline as render.
#include "apps/commands.h"
#include "apps/options.h"
#include "core/image/image_io.h"
#include "core/util/error.h"

#include <filesystem>
#include <memory>

namespace irad::apps {

namespace {

struct ConvertArgs {
  std::string input;
  std::vector<std::string> outputs;
  float exposure = 0.0f;
  std::string tone_map = "clamp";
};

int run_convert(const ConvertArgs& args) {
  for (const std::string& o : args.outputs) {
    image_format_of(o);
    require_writable(o, "-o");
  }
  const Image image = read_exr(args.input);
  PngOptions png;
  png.exposure = args.exposure;
  png.tone_map = args.tone_map == "reinhard" ? ToneMap::Reinhard : ToneMap::Clamp;
  for (const std::string& o : args.outputs) write_image(o, image, png);
  return 0;
}

} // namespace

void add_convert_command(CLI::App& app, Commands& commands) {
  auto args = std::make_shared<ConvertArgs>();
  CLI::App* cmd = app.add_subcommand("convert", "Re-encode a linear EXR as PNG (or EXR)");
  cmd->add_option("input", args->input, "Linear EXR")->required();
  cmd->add_option("-o,--output", args->outputs, "Output image (.png or .exr)")->required();
  cmd->add_option("--exposure", args->exposure, "PNG exposure in stops (EV)")
      ->capture_default_str();
  cmd->add_option("--tonemap", args->tone_map, "PNG tone map")
      ->check(CLI::IsMember({"clamp", "reinhard"}))
      ->capture_default_str();
  cmd->callback([args, &commands] { commands.selected = [args] { return run_convert(*args); }; });
}

} // namespace irad::apps
