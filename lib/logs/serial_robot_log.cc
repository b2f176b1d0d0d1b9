#include "logs/serial_robot_log.h"

#include <fmt/format.h>

#include "core/errors.h"
#include "models/serial_dynamics.h"

namespace driveid {

std::vector<std::string> SerialRobotLogColumns(const SerialRobot& robot) {
  std::vector<std::string> columns = {"t"};
  const std::vector<std::string> names = SerialCoordinateNames(robot);
  for (std::size_t j = 0; j < names.size(); ++j) {
    const std::string& name = names[j];
    columns.push_back(fmt::format("q_{}|q{}", name, j + 1));
    columns.push_back(fmt::format("?qd_{}|qd{}", name, j + 1));
    columns.push_back(fmt::format("tau_{}|tau{}", name, j + 1));
  }
  return columns;
}

SerialRobotLog MakeSerialRobotLog(const SerialRobot& robot, CsvLog csv) {
  const std::size_t n = SerialCoordinates(robot).size();
  if (csv.columns.size() != 1 + 3 * n) {
    throw std::logic_error("MakeSerialRobotLog: the columns of SerialRobotLogColumns are expected");
  }
  SerialRobotLog log;
  log.path = csv.path;
  log.time = std::move(csv.columns[0]);
  log.rate.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    log.position.push_back(std::move(csv.columns[1 + 3 * j]));
    log.rate[j] = std::move(csv.columns[2 + 3 * j]);
    log.torque.push_back(std::move(csv.columns[3 + 3 * j]));
  }
  for (std::size_t k = 1; k < log.time.size(); ++k) {
    if (!(log.time[k] > log.time[k - 1])) {
      const int line = k < csv.line_numbers.size() ? csv.line_numbers[k] : 0;
      throw InputError(line > 0 ? fmt::format("{}:{}: time does not increase", log.path, line)
                                : fmt::format("{}: time does not increase at sample {}", log.path, k + 1));
    }
  }
  return log;
}

}  // namespace driveid
