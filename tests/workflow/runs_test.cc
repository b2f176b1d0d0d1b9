// The workflow's runs on the shipped logs (data/, made by `simulate`): what
// a run adds to its fit — the C-drive's eq. (31) compensation for the
// friction fit only, traces and panels only when asked for, one panel per
// log and the residuals; the robot's Fig. 7 trace and panels; the report
// of a parameter file; and refusals of invalid options before any fit.
#include <algorithm>
#include <cstdlib>
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "logs/cdrive_log.h"
#include "logs/csv_log.h"
#include "params/parameter_file.h"
#include "logs/robot_log.h"
#include "workflow/cdrive_compensation.h"
#include "workflow/cdrive_identification.h"
#include "workflow/cdrive_simulation.h"
#include "workflow/parameter_report.h"
#include "workflow/robot_identification.h"

using namespace driveid;

namespace {

std::string Data(const std::string& name) {
  const char* source = std::getenv("DRIVEID_SOURCE_DIR");
  return std::string(source ? source : ".") + "/data/" + name;
}

}  // namespace

TEST_CASE("C-drive run: the compensation with the friction fit, traces and panels only when asked") {
  const ParameterFile start = ReadParameterFile(Data("cdrive_start.yaml"));
  std::vector<CDriveLog> logs;
  for (const char* name : {"cdrive_slow_translation.csv", "cdrive_slow_rotation.csv"}) {
    logs.push_back(ParseCDriveLog(Data(name), ReadFileToString(Data(name)), {}, 0.0));
  }
  CDriveIdentificationOptions options;
  options.fit.half_window = CDriveDefaultHalfWindow(CDriveFitKind::kFriction);
  const CDriveIdentification plain = IdentifyCDrive(logs, start, "cdrive_start.yaml", options);
  REQUIRE(plain.feedforward.has_value());
  CHECK_FALSE(plain.feedforward->gains.empty());
  CHECK(plain.model == "cdrive friction (28)");
  CHECK(plain.panels.size() == 1);  // the residuals' panel, empty
  CHECK(plain.panels.front().lines.empty());
  CHECK(plain.trace_csv.find("\n1,") == std::string::npos);
  options.trace = true;
  options.plot = true;
  const CDriveIdentification traced = IdentifyCDrive(logs, start, "cdrive_start.yaml", options);
  CHECK(traced.panels.size() == logs.size() + 1);
  CHECK(traced.panels.back().lines.size() == 2 * logs.size());
  CHECK(traced.trace_csv.find("\n2,") != std::string::npos);
  // The estimates do not depend on what is traced.
  REQUIRE(traced.fit.estimates.size() == plain.fit.estimates.size());
  for (std::size_t i = 0; i < plain.fit.estimates.size(); ++i) {
    CHECK(traced.fit.estimates[i].value == plain.fit.estimates[i].value);
  }
  CHECK(CDriveDefaultHalfWindow(CDriveFitKind::kInertia) < CDriveDefaultHalfWindow(CDriveFitKind::kFriction));
  options.fit.half_window = 0.0;
  CHECK_THROWS_WITH(IdentifyCDrive(logs, start, "cdrive_start.yaml", options),
                    "‹window› = 0: violated constraint: window > 0 s");
  CHECK_THROWS_WITH(IdentifyCDrive(logs, ParameterFile{}, "empty.yaml", options), "empty.yaml: no 'cdrive' section");
}

TEST_CASE("robot run: the Fig. 7 trace only when asked, motor 1's panel and the residuals of three motors") {
  const ParameterFile start = ReadParameterFile(Data("robot_start.yaml"));
  const std::string path = Data("robot_triangle.csv");
  const std::vector<RobotLog> logs = {ParseRobotLog(path, ReadFileToString(path), {})};
  RobotIdentificationOptions options;
  const PlanarRobotParameters initial = MakePlanarRobotParameters(*start.Find<PlanarRobotSection>());
  const RobotIdentification plain = IdentifyRobot(logs, initial, options);
  CHECK(plain.panels.size() == 2);
  CHECK(plain.panels.back().lines.size() == 3);
  CHECK(std::count(plain.trace_csv.begin(), plain.trace_csv.end(), '\n') == 2);  // comment and header
  options.trace = true;
  const RobotIdentification traced = IdentifyRobot(logs, initial, options);
  CHECK(std::count(traced.trace_csv.begin(), traced.trace_csv.end(), '\n') > 1000);
  CHECK(traced.params.output_inertia == plain.params.output_inertia);
  options.fit.fit.max_iterations = 0;
  CHECK_THROWS_AS(IdentifyRobot(logs, initial, options), OptionError);
}

TEST_CASE("parameter report: one block per section; a file without any refused by name") {
  const ParameterFile paper = ReadParameterFile(Data("paper000.yaml"));
  ParameterReportRequest request;
  request.path = "paper000.yaml";
  const ParameterReport text = ReportParameterFile(paper, request, false);
  CHECK_FALSE(text.text.empty());
  const ParameterReport json = ReportParameterFile(paper, request, true);
  CHECK(json.json.contains("drivetrain"));
  CHECK(json.text.empty());
  CHECK_THROWS_WITH(ReportParameterFile(ParameterFile{}, request, false), Catch::StartsWith("paper000.yaml: no "));
  // A fitted file for comparison must hold fit estimates.
  const ParameterFile axis = ReadParameterFile(Data("axis_example.yaml"));
  request.fitted = &axis;
  request.fitted_path = "axis_example.yaml";
  const ParameterFile robot = ReadParameterFile(Data("robot_paper000.yaml"));
  CHECK_THROWS_WITH(ReportParameterFile(robot, request, false), Catch::Contains("has no fit.estimates"));
}

TEST_CASE("C-drive simulation: the trace and panels only when asked for, the log and summary the same either way") {
  const ParameterFile table1 = ReadParameterFile(Data("cdrive_table1.yaml"));
  CDriveSimulationRequest request;
  request.program = "rotation";
  request.stroke = 0.5;
  const CDriveSimulation plain = SimulateCDrive(table1, "t.yaml", request, "cmd");
  request.trace = true;
  const CDriveSimulation traced = SimulateCDrive(table1, "t.yaml", request, "cmd");
  request.trace = false;
  request.plot = true;
  const CDriveSimulation plotted = SimulateCDrive(table1, "t.yaml", request, "cmd");
  CHECK(plain.trace_csv.empty());
  CHECK(plain.panels.empty());
  CHECK(std::count(traced.trace_csv.begin(), traced.trace_csv.end(), '\n') > 1000);
  CHECK(traced.panels.empty());
  CHECK(plotted.trace_csv.empty());
  REQUIRE(plotted.panels.size() == 2);
  CHECK(plain.log_text == traced.log_text);
  CHECK(plain.log_text == plotted.log_text);
  CHECK(plain.summary == traced.summary);
  CHECK(plain.summary_json == traced.summary_json);
}
