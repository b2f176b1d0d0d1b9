#include "io/joint_log.h"

#include <fmt/format.h>

#include "core/errors.h"
#include "io/csv_log.h"

namespace driveid {

const std::vector<std::string>& JointLogColumns() {
  static const std::vector<std::string> columns = {"t", "q_motor", "q_link", "tau|i"};
  return columns;
}

JointLog MakeJointLog(CsvLog csv, double torque_constant) {
  const std::string path = csv.label();
  JointLog log{path, std::move(csv.columns[0]), std::move(csv.columns[1]), std::move(csv.columns[2]),
               std::move(csv.columns[3])};
  if (csv.names[3] == "i") {
    if (!(torque_constant > 0.0)) {
      throw InputError(fmt::format("{}: the log has a current column 'i': joint.k_t must be given in --params", path));
    }
    for (double& v : log.torque) v *= torque_constant;
  }
  return log;
}

}  // namespace driveid
