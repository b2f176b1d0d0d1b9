#include "io/joint_log.h"

#include <fmt/format.h>

#include "core/errors.h"
#include "io/csv_log.h"

namespace driveid {

const std::vector<std::string>& JointLogColumns() {
  static const std::vector<std::string> columns = {"t", "q_motor", "q_link", "?tau|i", "?tau_link", "?qd_motor", "?qd_link"};
  return columns;
}

JointLog MakeJointLog(CsvLog csv, double torque_constant) {
  const std::string path = csv.label();
  JointLog log{path, std::move(csv.columns[0]), std::move(csv.columns[1]), std::move(csv.columns[2]),
               std::move(csv.columns[3]), std::move(csv.columns[4]), std::move(csv.columns[5]), std::move(csv.columns[6])};
  if (log.torque.empty() && log.link_torque.empty()) {
    throw InputError(fmt::format("{}: a joint log needs the motor torque tau (or the current i) or the shaft torque "
                                 "tau_link (map them with --col tau=COLUMN, --col tau_link=COLUMN)",
                                 path));
  }
  if (!log.torque.empty() && csv.names[3] == "i") {
    if (!(torque_constant > 0.0)) {
      throw InputError(fmt::format("{}: the log has a current column 'i': joint.k_t must be given in --params", path));
    }
    for (double& v : log.torque) v *= torque_constant;
  }
  return log;
}

std::string FormatJointExperimentLog(const JointExperimentLog& log, const std::vector<std::string>& comments) {
  std::string out;
  for (const auto& c : comments) out += "# " + c + "\n";
  out += "t,tau,q_motor,qd_motor,q_link,r\n";
  for (std::size_t i = 0; i < log.t.size(); ++i) {
    out += fmt::format("{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", log.t[i], log.tau[i], log.q_motor[i],
                       log.qd_motor[i], log.q_link[i], log.r[i]);
  }
  return out;
}

}  // namespace driveid
