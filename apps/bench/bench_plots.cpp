// The bench's plots, drawn by gnuplot (Debian's gnuplot-nox, pngcairo terminal): one data file
// per series and one script per plot, both left in the output folder so a plot can be redrawn.
#include "apps/bench/bench.h"
#include "core/util/error.h"

#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <set>

namespace irad::apps {

namespace {

struct Series {
  std::string title;
  std::string file;
  std::vector<double> x, y;
};

void write_series(const Series& s) {
  std::ofstream out(s.file);
  for (std::size_t i = 0; i < s.x.size(); ++i) out << s.x[i] << ' ' << s.y[i] << '\n';
  if (!out) throw Error(s.file, "", "cannot write");
}

void plot(const std::string& png, const std::string& title, const std::string& xlabel,
          const std::string& ylabel, const std::vector<Series>& series, Log& log) {
  const std::string script = png.substr(0, png.size() - 4) + ".gp";
  {
    std::ofstream gp(script);
    gp << "set terminal pngcairo size 800,560 font 'sans,10'\n"
       << "set output '" << png << "'\n"
       << "set title '" << title << "'\nset xlabel '" << xlabel << "'\nset ylabel '" << ylabel
       << "'\nset logscale xy\nset grid\nset key top right\nset format y '%.0e'\n";
    gp << "plot ";
    for (std::size_t i = 0; i < series.size(); ++i)
      gp << (i ? ", " : "") << "'" << series[i].file << "' with linespoints pt 7 ps 0.8 title '"
         << series[i].title << "'";
    gp << '\n';
  }
  for (const Series& s : series) write_series(s);
  const std::string command = "gnuplot '" + script + "' 2>&1";
  if (std::system(command.c_str()) != 0) throw Error(script, "gnuplot", "failed to draw " + png);
  log.info("bench: wrote " + png);
}

} // namespace

double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  const double d = n * sxx - sx * sx;
  return d != 0.0 ? (n * sxy - sx * sy) / d : 0.0;
}

void write_bench_plots(const std::vector<BenchRow>& rows, const std::string& out_dir, Log& log) {
  std::set<std::string> scenes;
  for (const BenchRow& r : rows) scenes.insert(r.scene);
  for (const std::string& scene : scenes) {
    // Error against time: raster (Halton), rt-vpl, pt.
    std::map<std::string, Series> by_estimator, by_estimator_block;
    std::map<std::string, Series> by_sequence;
    for (const BenchRow& r : rows) {
      if (r.scene != scene || !(r.relmse > 0.0)) continue;
      if (r.sequence.empty() || r.sequence == "halton") {
        Series& s = by_estimator[r.estimator];
        s.title = r.estimator;
        s.file = fmt::format("{}/plot_{}_time_{}.dat", out_dir, scene, r.estimator);
        s.x.push_back(r.total);
        s.y.push_back(r.relmse);
        Series& b = by_estimator_block[r.estimator];
        b.title = r.estimator;
        b.file = fmt::format("{}/plot_{}_time_block4_{}.dat", out_dir, scene, r.estimator);
        b.x.push_back(r.total);
        b.y.push_back(r.relmse_block4);
      }
      if (r.estimator == "raster") {
        Series& s = by_sequence[r.sequence];
        s.file = fmt::format("{}/plot_{}_paths_{}.dat", out_dir, scene, r.sequence);
        s.x.push_back(r.paths);
        s.y.push_back(r.relmse);
      }
    }
    std::vector<Series> time_series, block_series, path_series;
    for (auto& [name, s] : by_estimator) time_series.push_back(s);
    for (auto& [name, s] : by_estimator_block) block_series.push_back(s);
    for (auto& [name, s] : by_sequence) {
      s.title = fmt::format("{} (slope {:.2f})", name, loglog_slope(s.x, s.y));
      path_series.push_back(s);
    }
    if (!time_series.empty())
      plot(fmt::format("{}/error_vs_time_{}.png", out_dir, scene), scene + ": error against time",
           "seconds", "relMSE", time_series, log);
    if (!block_series.empty())
      plot(fmt::format("{}/error_vs_time_block4_{}.png", out_dir, scene),
           scene + ": error of the 4x4-block means against time", "seconds", "relMSE (4x4 blocks)",
           block_series, log);
    if (!path_series.empty())
      plot(fmt::format("{}/error_vs_paths_{}.png", out_dir, scene),
           scene + ": raster error against the number of paths N", "paths N", "relMSE", path_series,
           log);
  }
}

} // namespace irad::apps
