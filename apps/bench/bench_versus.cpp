// The bench's rows against pt at equal time (apps/bench/bench.h write_versus_pt): where each
// estimator wins, read off the CSV instead of the plots.
#include "apps/bench/bench.h"
#include "core/util/error.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <map>

namespace irad::apps {

std::optional<double> loglog_at(const std::vector<std::pair<double, double>>& curve, double x) {
  for (std::size_t i = 0; i + 1 < curve.size(); ++i) {
    const auto [x0, y0] = curve[i];
    const auto [x1, y1] = curve[i + 1];
    if (!(x0 > 0.0 && y0 > 0.0 && x1 > x0 && y1 > 0.0) || x < x0 || x > x1) continue;
    const double t = std::log(x / x0) / std::log(x1 / x0);
    return std::exp(std::log(y0) + t * (std::log(y1) - std::log(y0)));
  }
  return std::nullopt;
}

namespace {

// One scene's pt rows as two curves against time (per pixel, per 4x4 block), time ascending.
struct PtCurves {
  std::vector<std::pair<double, double>> pixel, block;
};

std::map<std::string, PtCurves> pt_curves(const std::vector<BenchRow>& rows) {
  std::map<std::string, PtCurves> curves;
  for (const BenchRow& r : rows)
    if (r.estimator == "pt" && r.total > 0.0) {
      curves[r.scene].pixel.emplace_back(r.total, r.relmse);
      curves[r.scene].block.emplace_back(r.total, r.relmse_block4);
    }
  for (auto& [scene, c] : curves) {
    std::sort(c.pixel.begin(), c.pixel.end());
    std::sort(c.block.begin(), c.block.end());
  }
  return curves;
}

} // namespace

void write_versus_pt(const std::vector<BenchRow>& rows, const std::string& path, Log& log) {
  const std::map<std::string, PtCurves> curves = pt_curves(rows);
  std::ofstream out(path);
  out << "scene,estimator,sequence,paths,rounds,seconds_total,relmse,pt_relmse,ratio,"
         "relmse_block4,pt_relmse_block4,ratio_block4\n";
  for (const BenchRow& r : rows) {
    const auto c = curves.find(r.scene);
    if (r.estimator == "pt" || c == curves.end()) continue;
    const std::optional<double> pixel = loglog_at(c->second.pixel, r.total);
    const std::optional<double> block = loglog_at(c->second.block, r.total);
    if (!pixel || !block) continue; // outside pt's times
    const double ratio = r.relmse / *pixel, ratio_block = r.relmse_block4 / *block;
    out << fmt::format("{},{},{},{},{},{:.6f},{:.6g},{:.6g},{:.4f},{:.6g},{:.6g},{:.4f}\n", r.scene,
                       r.estimator, r.sequence, r.paths, r.rounds, r.total, r.relmse, *pixel, ratio,
                       r.relmse_block4, *block, ratio_block);
    if (r.rounds > 0)
      log.info(fmt::format("bench: {} {} rounds {}: {:.2f} s, {:.2f}x pt's relMSE per pixel, "
                           "{:.2f}x per 4x4 block",
                           r.scene, r.estimator, r.rounds, r.total, ratio, ratio_block));
  }
  if (!out) throw Error(path, "", "cannot write");
}

} // namespace irad::apps
