#include "workflow/serial_robot_validation.h"

#include <cmath>

#include <fmt/format.h>

#include "core/errors.h"
#include "fit/adequacy.h"
#include "fit/serial_robot_fit.h"
#include "models/serial_dynamics.h"

namespace driveid {
namespace {

// The section's base parameters must be the URDF's own: same lead columns
// and combinations (coefficients as written, 10 digits).
std::vector<double> MatchedValues(const SerialRobotSection& section, const BaseParameters& base,
                                  const std::vector<std::string>& names, const std::string& path) {
  if (section.base.size() != base.base.size()) {
    throw InputError(fmt::format("{}: serial_robot.base has {} base parameters, the URDF's robot {}: the file was "
                                 "written for another robot or URDF",
                                 path, section.base.size(), base.base.size()));
  }
  std::vector<double> values;
  for (std::size_t k = 0; k < base.base.size(); ++k) {
    const SerialBaseEntry& e = section.base[k];
    bool same = e.lead == names[base.base[k]] && e.combination.size() == base.combination[k].size();
    for (std::size_t i = 0; same && i < e.combination.size(); ++i) {
      const auto& [column, c] = base.combination[k][i];
      same = e.combination[i].first == names[column] && std::abs(e.combination[i].second - c) <= 1e-9 * (1.0 + std::abs(c));
    }
    if (!same) {
      throw InputError(fmt::format("{}: serial_robot.base[{}] ({}) is not the URDF's base parameter {} ({}): the file "
                                   "was written for another robot or URDF",
                                   path, k, e.lead, names[base.base[k]], base.names[k]));
    }
    values.push_back(e.value);
  }
  return values;
}

}  // namespace

ValidationRun RunSerialRobotValidation(const std::vector<SerialRobotLog>& logs, const SerialRobotSection& section,
                                       const SerialRobot& robot, const std::string& path) {
  const BaseParameters base = SerialBaseParameters(robot);
  const std::vector<double> values = MatchedValues(section, base, SerialParameterNames(robot), path);
  ValidationRun run;
  run.method = "serial robot: each joint's torque by inverse dynamics of the base parameters (docs/models.md#serial-robot)";
  run.title = "serial robot validation: joint torques predicted from the parameter file";
  run.unit = "torque [N m or N]";
  for (const SerialRobotLog& log : logs) {
    const SerialPrediction p = PredictSerialRobot(robot, base, values, log, section.half_window);
    for (std::size_t j = 0; j < robot.size(); ++j) {
      ValidatedLog v;
      v.time = p.time;
      v.measured = p.measured[j];
      v.model = p.predicted[j];
      std::vector<double> residual(v.time.size());
      for (std::size_t k = 0; k < residual.size(); ++k) residual[k] = v.measured[k] - v.model[k];
      v.stats = DescribeResiduals(fmt::format("{}:tau_{}", log.path, robot.joints[j].name), v.measured.data(),
                                  residual.data(), static_cast<int>(residual.size()));
      run.logs.push_back(std::move(v));
    }
  }
  RequireValidated(run.logs);
  return run;
}

}  // namespace driveid
