// report/frf_report.h: the CSV holds |H| and arg H in degrees per bin, its
// std columns (|H| times the log-magnitude std, the phase std in degrees);
// the Bode panels show the magnitude in dB; the summary and the JSON carry
// the method.
#include "report/frf_report.h"

#include <cmath>
#include <sstream>

#include <catch2/catch.hpp>

using namespace driveid;

TEST_CASE("frf report: magnitude, phase and their stds in the CSV, dB in the Bode plot") {
  FrfResult result;
  result.rate = 1000.0;
  FrequencyResponse& m = result.motor;
  m.frequency = {1.0, 2.0, 4.0};
  m.response = {std::polar(2.0, -M_PI / 2.0), std::polar(0.5, M_PI / 4.0), std::polar(10.0, -M_PI)};
  m.coherence = {0.99, 0.9, 0.3};
  m.log_magnitude_std = {0.01, 0.02, 0.5};
  m.phase_std = {0.01, 0.02, 0.5};
  m.description = "Welch H1 (test)";
  const std::string csv = FormatFrfCsv(result);
  std::istringstream lines(csv);
  std::string line;
  std::vector<std::vector<double>> rows;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 'f') continue;
    std::vector<double> row;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  REQUIRE(rows.size() == 3);
  CHECK(rows[0][0] == 1.0);
  CHECK(rows[0][1] == Approx(2.0));
  CHECK(rows[0][2] == Approx(-90.0));
  CHECK(rows[1][2] == Approx(45.0));
  CHECK(rows[2][3] == Approx(0.3));
  CHECK(rows[1][4] == Approx(0.5 * 0.02).epsilon(0.05));           // |H| x std of ln |H|
  CHECK(rows[1][5] == Approx(0.02 * 180.0 / M_PI).epsilon(1e-3));  // degrees
  const std::vector<PlotPanel> panels = MakeBodePanels(result);
  REQUIRE_FALSE(panels.empty());
  bool db = false;
  for (const auto& line_ : panels.front().lines) {
    for (std::size_t k = 0; k < line_.y.size(); ++k) db = db || std::abs(line_.y[k] - 20.0 * std::log10(2.0)) < 1e-9;
  }
  CHECK(db);
  CHECK(FormatFrfSummary(result).find("Welch H1 (test)") != std::string::npos);
  CHECK(FrfJson(result).dump().find("Welch H1 (test)") != std::string::npos);
}
