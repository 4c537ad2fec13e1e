// The bench's comparison at equal time (apps/bench/bench_versus.cpp): pt's error interpolated on
// the log-log line between its rows, and the ratios written per row.
#include "apps/bench/bench.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <string>

namespace irad::apps {
namespace IRAD_UNITY_ID {

// On a power law the log-log line is exact: y = 3 x^-1.5 through x = 1, 4, 16.
TEST(BenchVersus, LogLogLineFollowsAPowerLaw) {
  const auto y = [](double x) { return 3.0 * std::pow(x, -1.5); };
  const std::vector<std::pair<double, double>> curve = {
      {1.0, y(1.0)}, {4.0, y(4.0)}, {16.0, y(16.0)}};
  for (double x : {1.0, 2.0, 4.0, 7.5, 16.0}) {
    const std::optional<double> at = loglog_at(curve, x);
    ASSERT_TRUE(at.has_value()) << x;
    EXPECT_NEAR(*at / y(x), 1.0, 1e-12) << x;
  }
  EXPECT_FALSE(loglog_at(curve, 0.5).has_value());
  EXPECT_FALSE(loglog_at(curve, 17.0).has_value());
  EXPECT_FALSE(loglog_at({{1.0, 1.0}}, 1.0).has_value());
}

// A row at 2 s between pt's rows at 1 s and 4 s (relMSE falling as 1/t): pt there is 5e-3 per
// pixel and 5e-4 per block, so the row's 2.5e-3 and 1e-4 are 0.5x and 0.2x; a row past pt's
// last time is left out.
TEST(BenchVersus, RowsAgainstPtAtTheirOwnTime) {
  std::vector<BenchRow> rows(4);
  rows[0].estimator = rows[1].estimator = "pt";
  rows[0].total = 1.0, rows[0].relmse = 1e-2, rows[0].relmse_block4 = 1e-3;
  rows[1].total = 4.0, rows[1].relmse = 2.5e-3, rows[1].relmse_block4 = 2.5e-4;
  rows[2].estimator = "raster-default", rows[2].rounds = 2;
  rows[2].total = 2.0, rows[2].relmse = 2.5e-3, rows[2].relmse_block4 = 1e-4;
  rows[3].estimator = "rt-vpl-default", rows[3].rounds = 8;
  rows[3].total = 10.0, rows[3].relmse = 1e-3, rows[3].relmse_block4 = 1e-4;
  for (BenchRow& r : rows) r.scene = "cornell";
  const std::string path =
      (std::filesystem::temp_directory_path() / "irad_test_versus_pt.csv").string();
  Log log([](const std::string&) {});
  write_versus_pt(rows, path, log);
  std::ifstream in(path);
  std::string header, line, extra;
  ASSERT_TRUE(std::getline(in, header));
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_FALSE(std::getline(in, extra)) << extra;
  std::filesystem::remove(path);
  std::vector<std::string> cells;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
  ASSERT_EQ(cells.size(), 12u) << line;
  EXPECT_EQ(cells[1], "raster-default");
  EXPECT_EQ(cells[4], "2");
  EXPECT_NEAR(std::stod(cells[7]), 5e-3, 1e-9);
  EXPECT_NEAR(std::stod(cells[8]), 0.5, 1e-4);
  EXPECT_NEAR(std::stod(cells[10]), 5e-4, 1e-10);
  EXPECT_NEAR(std::stod(cells[11]), 0.2, 1e-4);
}

} // namespace
} // namespace irad::apps
