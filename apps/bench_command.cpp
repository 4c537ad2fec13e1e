// irad bench [--quick] [-o DIR] [--scene NAME]...: speed against error (apps/bench.h).
#include "apps/bench.h"
#include "apps/commands.h"

#include <memory>

namespace irad::apps {

void add_bench_command(CLI::App& app, Commands& commands) {
  auto options = std::make_shared<BenchOptions>();
  auto quiet = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("bench", "Speed against error: sweep N, sequence, estimator");
  cmd->add_flag("--quick", options->quick, "A smoke run (well under 2 minutes)");
  cmd->add_option("-o,--output", options->out_dir, "Output folder (CSV, plots, cached references)")
      ->capture_default_str();
  cmd->add_option("--cornell", options->cornell, "The Cornell box glTF")->capture_default_str();
  cmd->add_option("--scene", options->scenes, "Only these scenes: cornell, sphere, large")
      ->check(CLI::IsMember({"cornell", "sphere", "large"}));
  cmd->add_option("--size", options->size, "Image side (default 64 quick, 256 full)");
  cmd->add_option("--reference-spp", options->reference_spp,
                  "Path-traced reference samples per pixel (default 256 quick, 4096 full)");
  cmd->add_flag(
      "--no-plots", [options](std::int64_t) { options->plots = false; }, "Write the CSV only");
  cmd->add_flag(
      "--no-scale", [options](std::int64_t) { options->scale = false; },
      "Skip the triangle-count study");
  cmd->add_flag("-q,--quiet", *quiet, "No progress lines");
  cmd->callback([options, quiet, &commands] {
    commands.selected = [options, quiet] {
      Log log;
      log.set_quiet(*quiet);
      run_bench(*options, log);
      return 0;
    };
  });
}

} // namespace irad::apps
