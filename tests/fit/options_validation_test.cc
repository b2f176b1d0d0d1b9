// Options structs validate themselves in one place each (IsValid, as
// Ceres's Solver::Options): the message names the field between the
// library's marks (the tools print the flag) and the constraint, and the
// fits refuse invalid options with that message before reading any log.
#include <catch2/catch.hpp>

#include "core/errors.h"
#include "fit/axis_fit.h"
#include "fit/cdrive_fit.h"
#include "fit/joint_fit.h"
#include "fit/robot_fit.h"

using namespace driveid;

TEST_CASE("options structs validate themselves, naming the field and the constraint") {
  std::string error;
  AxisFitOptions axis;
  CHECK(axis.IsValid(&error));
  axis.decimation = 0;
  CHECK_FALSE(axis.IsValid(&error));
  CHECK(error == "‹decimation› = 0: violated constraint: >= 1");
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
  axis.decimation = 0;
  CHECK_THROWS_AS(FitAxis({log}, AxisSection{}, axis), OptionError);
  CHECK_THROWS_WITH(FitAxis({log}, AxisSection{}, axis), "‹decimation› = 0: violated constraint: >= 1");
  CDriveFitOptions cdrive;
  cdrive.half_window = -1.0;
  CDriveLog c{"c.csv", {0.0, 0.1}, {0.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}};
  CHECK_THROWS_WITH(FitCDriveFriction({c}, CDriveSection{}, cdrive), "‹window› = -1: violated constraint: window > 0 s");
  JointFitOptions joint;
  joint.cutoff = -1.0;
  CHECK_THROWS_WITH(FitJoint({}, JointSection{}, joint), "‹cutoff› = -1: violated constraint: cutoff > 0 Hz (0: rate / 40)");
}
