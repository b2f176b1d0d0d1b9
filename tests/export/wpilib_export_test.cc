// export/wpilib_export.h: the gains reach WPILib's classes with all their
// digits: SimpleMotorFeedforward(kS, kV, kA) without gravity,
// ArmFeedforward(kS, kG, kV, kA) with it, ElevatorFeedforward on a linear
// axis with its offset as kG; C++ in the units library's types, refused for an effort that is not
// volts.
#include "export/wpilib_export.h"

#include <catch2/catch.hpp>

#include "core/errors.h"

using namespace driveid;

namespace {

Feedforward Gains(bool gravity) {
  Feedforward f;
  f.effort_unit = "V";
  f.position_unit = "Radians";
  f.gains = {{"Ks", 0.125, 0.01, "V"}, {"Kv", 3.0625, 0.02, "V s/Radians"}, {"Ka", 0.3125, 0.003, "V s^2/Radians"}};
  if (gravity) f.gains.push_back({"Kg", 0.75, 0.01, "V"});
  return f;
}

}  // namespace

TEST_CASE("WPILib export: the class follows the fitted terms, the numbers keep their digits") {
  ExportOptions options;
  options.joint = "shooter";
  const Feedforward simple = Gains(false);
  const std::string java = ExportWpilibJava({simple}, options);
  CHECK(java.find("SimpleMotorFeedforward") != std::string::npos);
  CHECK(java.find("ArmFeedforward") == std::string::npos);
  for (const char* number : {"0.125", "3.0625", "0.3125"}) CHECK(java.find(number) != std::string::npos);
  const Feedforward arm = Gains(true);
  CHECK(ExportWpilibJava({arm}, options).find("ArmFeedforward") != std::string::npos);
  // A linear axis' constant force (the offset) is the elevator's kG.
  Feedforward lift = Gains(false);
  lift.gains.push_back({"offset", 0.5, 0.01, "V"});
  WpilibAxis linear{lift};
  linear.linear = true;
  CHECK(ExportWpilibJava(linear, options).find("ElevatorFeedforward") != std::string::npos);
  const std::string cpp = ExportWpilibCpp({simple}, options);
  CHECK(cpp.find("units::") != std::string::npos);
  Feedforward newton_metres = simple;
  newton_metres.effort_unit = "N m";
  CHECK_THROWS_AS(ExportWpilibCpp({newton_metres}, options), InputError);
}
