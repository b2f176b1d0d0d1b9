#include "logs/joint_log.h"

#include <fmt/format.h>

#include "core/errors.h"
#include "logs/csv_log.h"
#include "logs/log_columns.h"

namespace driveid {
namespace {
using L = JointLog;
constexpr LogColumn<L> kColumns[] = {
    RequiredColumn<L>("t", &FieldOf<L, &L::time>),
    RequiredColumn<L>("q_motor", &FieldOf<L, &L::motor_position>),
    RequiredColumn<L>("q_link", &FieldOf<L, &L::link_position>),
    OptionalColumn<L>("tau|i", &FieldOf<L, &L::torque>),
    OptionalColumn<L>("tau_link", &FieldOf<L, &L::link_torque>),
    OptionalColumn<L>("qd_motor", &FieldOf<L, &L::motor_rate>),
    OptionalColumn<L>("qd_link", &FieldOf<L, &L::link_rate>),
};
constexpr std::size_t kTorque = LogColumnIndex(kColumns, "tau|i");
static_assert(kTorque < std::size(kColumns), "joint log columns");
}  // namespace

const std::vector<std::string>& JointLogColumns() {
  static const std::vector<std::string> columns = LogColumnRequest(kColumns);
  return columns;
}

JointLog MakeJointLog(CsvLog csv, double torque_constant) {
  const bool current = csv.names[kTorque] == "i";
  JointLog log = MakeLogFromColumns(kColumns, csv);
  const std::string& path = log.path;
  if (log.torque.empty() && log.link_torque.empty()) {
    throw InputError(fmt::format("{}: a joint log needs the motor torque tau (or the current i) or the shaft torque "
                                 "tau_link (map them with ‹col› tau=COLUMN, ‹col› tau_link=COLUMN)",
                                 path));
  }
  if (!log.torque.empty() && current) {
    if (!(torque_constant > 0.0)) {
      throw InputError(fmt::format("{}: the log has a current column 'i': joint.k_t must be given in ‹params›", path));
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
