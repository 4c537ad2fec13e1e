// irad compare A.exr B.exr [--block K] [--diff OUT.png] [--diff-max F] [--json FILE]: the
// accuracy of image A against the reference B (see core/image/image_metrics.h for the metrics).
// Prints one line per metric on stdout; exits 0 whenever the images could be compared, however
// different.
#include "apps/commands.h"
#include "apps/options.h"
#include "core/image/image_io.h"
#include "core/image/image_metrics.h"
#include "core/util/error.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace irad::apps {

namespace {

struct CompareArgs {
  std::string image;
  std::string reference;
  int block = 1;
  std::string diff;
  double diff_max = 0.2;
  std::string json;
};

// Everything that can be checked before reading the images.
void check_args(const CompareArgs& args) {
  if (args.block < 1)
    throw Error("", "--block", fmt::format("{} is not a block size (at least 1)", args.block));
  if (!(args.diff_max > 0) || !std::isfinite(args.diff_max))
    throw Error("", "--diff-max", fmt::format("{} is not a positive number", args.diff_max));
  if (!args.diff.empty()) {
    image_format_of(args.diff);
    require_writable(args.diff, "--diff");
  }
  if (!args.json.empty()) require_writable(args.json, "--json");
}

// Non-finite values spelled "nan", "inf", "-inf" (whatever the NaN's sign bit), others as %.6g.
std::string number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{:.6g}", v);
}

// JSON has no NaN or Inf: those become the strings of number(); finite values stay numbers.
nlohmann::json json_number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(number(v));
}

nlohmann::json json_rgb(const std::array<double, 3>& v) {
  return {json_number(v[0]), json_number(v[1]), json_number(v[2])};
}

nlohmann::json metrics_json(const CompareArgs& args, const Image& image, const ImageMetrics& m) {
  return {{"image", args.image},
          {"reference", args.reference},
          {"size", {image.width(), image.height()}},
          {"block", m.block},
          {"rmse", json_number(m.rmse)},
          {"rmse_rgb", json_rgb(m.rmse_rgb)},
          {"relmse", json_number(m.relmse)},
          {"relmse_eps", kRelMseEpsilon},
          {"mean_ratio", json_rgb(m.mean_ratio)},
          {"max_abs_error", json_number(m.max_abs_error)},
          {"nonfinite", {m.nonfinite_a, m.nonfinite_b}},
          {"pixels", m.pixels},
          {"samples", m.samples}};
}

void print_report(const ImageMetrics& m) {
  const auto& c = m.rmse_rgb;
  const auto& r = m.mean_ratio;
  fmt::print("rmse {} (r {} g {} b {})\n", number(m.rmse), number(c[0]), number(c[1]),
             number(c[2]));
  fmt::print("relmse {}\n", number(m.relmse));
  fmt::print("mean_ratio {} {} {}\n", number(r[0]), number(r[1]), number(r[2]));
  fmt::print("max_abs_error {}\n", number(m.max_abs_error));
  fmt::print("nonfinite {} {}\n", m.nonfinite_a, m.nonfinite_b);
  fmt::print("pixels {}\n", m.pixels);
  fmt::print("samples {} (block {})\n", m.samples, m.block);
  std::fflush(stdout);
}

// Writes FILE.tmp and renames it over FILE, so FILE is complete or untouched; no .tmp is left.
void write_json(const std::string& path, const nlohmann::json& j) {
  const std::string tmp = path + ".tmp";
  std::error_code ec;
  {
    std::ofstream out(tmp);
    out << j.dump(2) << '\n';
    out.close();
    if (!out) {
      std::filesystem::remove(tmp, ec);
      throw Error(path, "--json", "cannot write");
    }
  }
  std::filesystem::rename(tmp, path, ec);
  if (!ec) return;
  const std::string reason = ec.message();
  std::filesystem::remove(tmp, ec);
  throw Error(path, "--json", "cannot write: " + reason);
}

// The files are written before the report is printed: a failure leaves no half report behind.
int run_compare(const CompareArgs& args) {
  check_args(args);
  const Image image = read_exr(args.image);
  const Image reference = read_exr(args.reference);
  require_same_size(image, args.image, reference, args.reference);
  const ImageMetrics m = compare_images(image, reference, args.block);
  if (!args.diff.empty()) {
    PngOptions png; // exposure 0, Clamp: the ramp colours are already display-ready
    write_image(args.diff, relative_error_image(image, reference, {args.diff_max, args.block}),
                png);
  }
  if (!args.json.empty()) write_json(args.json, metrics_json(args, image, m));
  print_report(m);
  return 0;
}

} // namespace

void add_compare_command(CLI::App& app, Commands& commands) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand("compare", "Accuracy of an EXR image against a reference EXR");
  cmd->add_option("image", args->image, "Image to assess (.exr)")->required();
  cmd->add_option("reference", args->reference, "Reference image (.exr)")->required();
  cmd->add_option("--block", args->block,
                  "Compare the means of KxK blocks (separates noise from bias)")
      ->capture_default_str();
  cmd->add_option("--diff", args->diff, "Write a false-colour relative error image (.png)");
  cmd->add_option("--diff-max", args->diff_max,
                  "Relative error shown as full red in --diff (0.2 = 20 %)")
      ->capture_default_str();
  cmd->add_option("--json", args->json, "Write the metrics as JSON to this file");
  cmd->callback([args, &commands] { commands.selected = [args] { return run_compare(*args); }; });
}

} // namespace irad::apps
