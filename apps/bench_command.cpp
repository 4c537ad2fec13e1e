// irad bench [--quick] [-o DIR] [--scene NAME,...] [--shared DIR]: speed against error
// (apps/bench/bench.h).
// irad bench --load FILE [--runs N] [-o DIR]: load, BVH and upload time and memory of one scene
// (apps/bench/load_bench.h).
#include "apps/bench/bench.h"
#include "apps/bench/bench_real_scenes.h"
#include "apps/bench/load_bench.h"
#include "apps/commands.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <memory>

namespace irad::apps {

void add_bench_command(CLI::App& app, Commands& commands) {
  auto options = std::make_shared<BenchOptions>();
  auto quiet = std::make_shared<bool>(false);
  auto load = std::make_shared<LoadBenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Speed against error: sweep N, sequence, estimator");
  cmd->add_flag("--quick", options->quick, "A smoke run (well under 2 minutes)");
  cmd->add_option("-o,--output", options->out_dir, "Output folder (CSV, plots, cached references)")
      ->capture_default_str();
  cmd->add_option("--cornell", options->cornell, "The Cornell box glTF")->capture_default_str();
  cmd->add_option("--scene", options->scenes,
                  "Only these scenes, comma-separated: cornell, sphere, large (the default set), "
                  "cornell_glossy (data/cornell_glossy.gltf beside --cornell), sphere2m (the "
                  "Cornell box with a sphere of 2.1M triangles), zdm2, godot (third-party levels "
                  "from --shared, with a light and camera added, Lambertian), godot_glossy (the "
                  "godot room with its own materials and metal spheres)")
      ->delimiter(',')
      ->check(CLI::IsMember({"cornell", "cornell_glossy", "sphere", "large", "sphere2m", "zdm2",
                             "godot", "godot_glossy"}));
  cmd->add_option("--shared", options->shared, "Folder of the third-party scenes (zdm2, godot)")
      ->capture_default_str();
  cmd->add_option("--size", options->size,
                  "Image side (default 64 quick, 256 full, 128 for sphere2m and the third-party "
                  "scenes)");
  cmd->add_option("--reference-spp", options->reference_spp,
                  "Path-traced reference samples per pixel (default 256 quick, 4096 full, 1024 for "
                  "sphere2m)");
  cmd->add_flag(
      "--no-plots", [options](std::int64_t) { options->plots = false; }, "Write the CSV only");
  cmd->add_flag(
      "--no-scale", [options](std::int64_t) { options->scale = false; },
      "Skip the triangle-count study (skipped anyway when only zdm2 and godot run)");
  cmd->add_flag("--scale-only", options->scale_only,
                "Only the triangle-count study (OUT/scale.csv; with --quick up to 32k "
                "triangles); with --scene zdm2,godot instead the shadow level of detail's error "
                "on them (OUT/shadow_lod_error.csv)");
  cmd->add_option("--load", load->file,
                  "Instead of the sweep: time and peak memory of loading this glTF/GLB (load, "
                  "BVH, GL upload); writes OUT/load.csv")
      ->check(CLI::ExistingFile);
  cmd->add_option("--runs", load->runs, "--load: runs (the times are medians)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_flag(
      "--no-raster", [load](std::int64_t) { load->raster = false; }, "--load: skip the GL stages");
  cmd->add_option("--memory-trace", load->memory_trace,
                  "--load: CSV of the resident set every millisecond of the first run");
  cmd->add_flag("-q,--quiet", *quiet, "No progress lines");
  cmd->callback([options, quiet, load, &commands] {
    commands.selected = [options, quiet, load] {
      Log log;
      log.set_quiet(*quiet);
      if (!load->file.empty()) {
        load->out_dir = options->out_dir;
        fmt::print("{}", load_table(run_load_bench(*load, log)));
        return 0;
      }
      if (options->scale_only) {
        std::filesystem::create_directories(options->out_dir);
        const bool real =
            std::any_of(options->scenes.begin(), options->scenes.end(), is_real_scene);
        if (real)
          run_shadow_lod_error(*options, log); // the real scenes only
        else
          run_scale_study(*options, log);
      } else
        run_bench(*options, log);
      return 0;
    };
  });
}

} // namespace irad::apps
