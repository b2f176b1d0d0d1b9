// Options structs validate themselves in one place each (IsValid, as
// Ceres's Solver::Options): the message names the field between the
// library's marks (the tools print the flag) and the constraint, and the
// fits refuse invalid options with that message before reading any log.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/errors.h"
#include "export/parameter_export.h"
#include "fit/axis/axis_fit.h"
#include "fit/axis/axis_oe_fit.h"
#include "fit/cdrive/cdrive_fit.h"
#include "fit/frf/frf_analysis.h"
#include "fit/joint/joint_fit.h"
#include "fit/joint/joint_oe_fit.h"
#include "fit/robot/robot_fit.h"
#include "fit/step/step_fit.h"
#include "logs/csv_log.h"
#include "logs/log_input.h"
#include "signal/frequency_response.h"
#include "sim/cdrive_closed_loop.h"
#include "sim/cvodes_integrator.h"
#include "sim/mujoco_axis_simulator.h"
#include "workflow/axis_identification.h"
#include "workflow/feedback_design.h"
#include "workflow/joint_identification.h"
#include "workflow/step_identification.h"
#include "workflow/validation_run.h"

using namespace driveid;

TEST_CASE("options structs validate themselves, naming the field and the constraint") {
  std::string error;
  AxisFitOptions axis;
  CHECK(axis.IsValid(&error));
  axis.decimation = kAxisDecimationFromLogs;  // 0: chosen from the logs
  CHECK(axis.IsValid(&error));
  axis.decimation = -1;
  CHECK_FALSE(axis.IsValid(&error));
  CHECK(error == "‹decimation› = -1: violated constraint: >= 1 (0: from the logs)");
  axis.decimation = 10;
  axis.cutoff = -1.0;
  CHECK_FALSE(axis.IsValid(&error));
  CHECK(error.rfind("‹cutoff› = -1: violated constraint", 0) == 0);

  CDriveFitOptions cdrive;
  CHECK(cdrive.IsValid(&error));
  cdrive.min_rate = -0.5;
  CHECK_FALSE(cdrive.IsValid(&error));
  CHECK(error == "‹min_rate› = -0.5: violated constraint: min rate >= 0");
  cdrive.half_window = 0.0;
  CHECK_FALSE(cdrive.IsValid(&error));
  CHECK(error == "‹window› = 0: violated constraint: window > 0 s");

  JointFitOptions joint;
  CHECK(joint.IsValid(&error));
  joint.cutoff = -2.0;  // was read as rate / 40
  CHECK_FALSE(joint.IsValid(&error));
  CHECK(error == "‹cutoff› = -2: violated constraint: cutoff > 0 Hz (0: rate / 40)");
  joint.cutoff = 0.0;
  joint.min_rate_fraction = 1.0;
  CHECK_FALSE(joint.IsValid(&error));
  CHECK(error == "min_rate_fraction = 1: violated constraint: 0 <= fraction < 1");

  RobotFitOptions robot;
  CHECK(robot.IsValid(&error));
  robot.half_window = -0.001;
  CHECK_FALSE(robot.IsValid(&error));
  CHECK(error == "‹window› = -0.001: violated constraint: > 0 s");
}

TEST_CASE("a fit refuses invalid options with their own message") {
  AxisLog log{"a.csv", {0.0, 0.1, 0.2}, {0.0, 0.1, 0.2}, {1.0, 1.0, 1.0}, {}};
  AxisFitOptions axis;
  axis.cutoff = 5.0;
  axis.decimation = -2;
  CHECK_THROWS_AS(FitAxis({log}, AxisSection{}, axis), OptionError);
  CHECK_THROWS_WITH(FitAxis({log}, AxisSection{}, axis), "‹decimation› = -2: violated constraint: >= 1 (0: from the logs)");
  CDriveFitOptions cdrive;
  cdrive.half_window = -1.0;
  CDriveLog c{"c.csv", {0.0, 0.1}, {0.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}};
  CHECK_THROWS_WITH(FitCDriveFriction({c}, CDriveSection{}, cdrive), "‹window› = -1: violated constraint: window > 0 s");
  JointFitOptions joint;
  joint.cutoff = -1.0;
  CHECK_THROWS_WITH(FitJoint({}, JointSection{}, joint), "‹cutoff› = -1: violated constraint: cutoff > 0 Hz (0: rate / 40)");
}

namespace {

// The defaults are valid; after `spoil`, IsValid refuses with `expected`.
template <typename Options, typename Spoil>
void CheckRefusal(Spoil spoil, const std::string& expected) {
  std::string error;
  Options options;
  CHECK(options.IsValid(&error));
  spoil(options);
  CHECK_FALSE(options.IsValid(&error));
  CHECK(error == expected);
}

}  // namespace

TEST_CASE("every options struct refuses a value outside its bounds, by field") {
  CheckRefusal<FitOptions>([](auto& o) { o.max_iterations = 0; }, "max_iterations = 0: violated constraint: >= 1");
  CheckRefusal<FitOptions>([](auto& o) { o.max_seconds = NAN; },
                           "‹max_seconds› = nan: violated constraint: max seconds >= 0 (0: no limit)");
  // Nested options report their own field.
  CheckRefusal<AxisOeOptions>([](auto& o) { o.fit.max_iterations = -1; },
                              "max_iterations = -1: violated constraint: >= 1");
  CheckRefusal<StepFitOptions>([](auto& o) { o.fit.identifiability_threshold = 1.0; },
                               "identifiability_threshold = 1: violated constraint: 0 <= threshold < 1");
  CheckRefusal<JointOeOptions>([](auto& o) { o.segment_seconds = -1.0; },
                               "‹segment› = -1: violated constraint: segment >= 0 s (0: auto, inf: whole log)");
  {
    JointOeOptions whole;  // single shooting
    whole.segment_seconds = INFINITY;
    std::string error;
    CHECK(whole.IsValid(&error));
  }
  CheckRefusal<TwoMassFitOptions>([](auto& o) { o.band_low = 10.0, o.band_high = 5.0; },
                                  "‹band› high = 5: violated constraint: above the low end (0, 0: the coherent bins)");
  CheckRefusal<TwoMassFitOptions>([](auto& o) { o.min_coherence = 1.5; },
                                  "min_coherence = 1.5: violated constraint: 0 <= coherence <= 1");
  CheckRefusal<FrequencyResponseOptions>([](auto& o) { o.resolution = -1.0; },
                                         "‹resolution› = -1: violated constraint: resolution >= 0 Hz (0: from the "
                                         "records)");
  CheckRefusal<FrfOptions>([](auto& o) { o.estimate.period = -0.5; },
                           "‹period› = -0.5: violated constraint: period >= 0 s (0: detected)");
  CheckRefusal<FrfOptions>([](auto& o) { o.two_mass.hold_rate = -1.0; },
                           "hold_rate = -1: violated constraint: rate >= 0 Hz (0: continuous)");
  CheckRefusal<AxisIdentificationOptions>([](auto& o) { o.axis.decimation = -1; },
                                          "‹decimation› = -1: violated constraint: >= 1 (0: from the logs)");
  CheckRefusal<JointIdentificationOptions>([](auto& o) { o.cutoff = -3.0; },
                                           "‹cutoff› = -3: violated constraint: cutoff > 0 Hz (0: rate / 40)");
  CheckRefusal<StepIdentificationOptions>([](auto& o) { o.fit.fit.max_iterations = 0; },
                                          "max_iterations = 0: violated constraint: >= 1");
  CheckRefusal<AxisValidationOptions>([](auto& o) { o.torque_timing = AxisTorqueTiming::kFromData; },
                                      "‹torque_timing› auto: a validation takes the timing the fit chose (the file's, sampled, held or "
                                      "a delay)");
  CheckRefusal<AxisGainsOptions>([](auto& o) { o.loop = "speed"; },
                                 "‹loop›: velocity or position for an axis (speed: an elastic joint's section)");
  CheckRefusal<AxisGainsOptions>([](auto& o) { o.period = 0.0; }, "‹period› = 0: violated constraint: period > 0 s");
  CheckRefusal<AxisGainsOptions>([](auto& o) { o.kv_std = -1.0; }, "‹kv_std› = -1: violated constraint: >= 0");
  CheckRefusal<JointGainsOptions>([](auto& o) { o.phase_margin_deg = 90.0; },
                                  "‹phase_margin› = 90: violated constraint: 0 < margin < 90 degrees");
  CheckRefusal<IntegratorOptions>([](auto& o) { o.absolute_tolerance = {1e-9, 0.0}; },
                                  "absolute_tolerance = 0: violated constraint: > 0 per state");
  CheckRefusal<MujocoAxisOptions>([](auto& o) { o.max_step = 0.0; },
                                  "‹mujoco_step› = 0: violated constraint: MuJoCo's largest step > 0 s");
  CheckRefusal<ClosedLoopOptions>([](auto& o) { o.cycles = 0; }, "‹cycles› = 0: violated constraint: 1 <= cycles <= 1000");
  CheckRefusal<LogInputOptions>([](auto& o) { o.from = 2.0, o.to = 1.0; }, "‹from› 2 ‹to› 1: need from < to");
  CheckRefusal<LogInputOptions>([](auto& o) { o.rate = -1.0; },
                                "‹rate› = -1: violated constraint: rate >= 0 Hz (0: the time column)");
  CheckRefusal<CsvReadOptions>([](auto& o) { o.column_map["q"] = ""; }, "‹col› 'q=': a name and a header");
  CheckRefusal<ExportOptions>([](auto& o) { o.joint = "a-b"; },
                              "‹joint›: joint name 'a-b': letters, digits and _ only, starting with a letter or _, at "
                              "most 64 (it becomes an XML name and a Java/C identifier)");
}

TEST_CASE("each run refuses invalid options before reading its input") {
  FrequencyResponseOptions estimate;
  estimate.resolution = -1.0;
  CHECK_THROWS_WITH(EstimateFrequencyResponse({}, 1000.0, estimate), Catch::StartsWith("‹resolution› = -1"));
  AxisOeOptions oe;
  oe.fit.max_iterations = 0;
  CHECK_THROWS_WITH(FitAxisOutputError({}, AxisSection{}, nullptr, oe), Catch::StartsWith("max_iterations = 0"));
  JointOeOptions joint_oe;
  joint_oe.segment_seconds = NAN;
  CHECK_THROWS_AS(FitJointOutputError({}, JointSection{}, nullptr, joint_oe), OptionError);
  ExportOptions export_options;
  export_options.joint = "";
  CHECK_THROWS_WITH(ExportParameters(ParameterFile{}, ExportTarget::kJson, export_options),
                    Catch::StartsWith("‹joint›: joint name ''"));
  LogInputOptions input;
  input.rate = NAN;
  CHECK_THROWS_WITH(ReadLogs("a.csv", "t,q\n0,0\n", {}, {"q"}, input), Catch::StartsWith("‹rate› = nan"));
  CsvReadOptions csv;
  csv.column_map[""] = "x";
  CHECK_THROWS_WITH(ParseCsvLog("a.csv", "t,x\n0,0\n", {"q"}, csv), "‹col› '=x': a name and a header");
}
