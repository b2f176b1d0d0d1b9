#include "io/cdrive_log.h"

#include <fmt/format.h>

#include "core/errors.h"
#include "io/csv_log.h"

namespace driveid {

const std::vector<std::string>& CDriveLogColumns() {
  static const std::vector<std::string> columns = {"t", "psi_L", "psi_R", "tau_L|i_L", "tau_R|i_R"};
  return columns;
}

CDriveLog ParseCDriveLog(const std::string& path, const std::string& text,
                         const std::map<std::string, std::string>& column_map, double torque_constant) {
  CsvReadOptions options;
  options.column_map = column_map;
  return MakeCDriveLog(ParseCsvLog(path, text, CDriveLogColumns(), options), torque_constant);
}

CDriveLog MakeCDriveLog(CsvLog csv, double torque_constant) {
  const std::string path = csv.label();
  CDriveLog log;
  log.path = path;
  log.time = std::move(csv.columns[0]);
  log.angle_left = std::move(csv.columns[1]);
  log.angle_right = std::move(csv.columns[2]);
  log.torque_left = std::move(csv.columns[3]);
  log.torque_right = std::move(csv.columns[4]);
  const bool left_current = csv.names[3] == "i_L", right_current = csv.names[4] == "i_R";
  if (left_current != right_current) {
    throw InputError(fmt::format("{}: give both motor torques (tau_L, tau_R) or both currents (i_L, i_R)", path));
  }
  if (left_current) {
    if (!(torque_constant > 0.0)) {
      throw InputError(fmt::format("{}: the log has currents i_L, i_R: cdrive.k_t must be given in --params", path));
    }
    for (double& v : log.torque_left) v *= torque_constant;
    for (double& v : log.torque_right) v *= torque_constant;
  }
  return log;
}

std::string FormatCDriveLog(const CDriveLog& log, const std::vector<std::string>& comments) {
  RequireFiniteColumns({{"t", &log.time}, {"psi_L", &log.angle_left}, {"psi_R", &log.angle_right},
                        {"tau_L", &log.torque_left}, {"tau_R", &log.torque_right}},
                       log.time);
  std::string out;
  for (const auto& line : comments) out += "# " + line + "\n";
  out += "t,psi_L,psi_R,tau_L,tau_R\n";
  for (std::size_t k = 0; k < log.time.size(); ++k) {
    out += fmt::format("{},{:.10g},{:.10g},{:.7g},{:.7g}\n", log.time[k], log.angle_left[k], log.angle_right[k],
                       log.torque_left[k], log.torque_right[k]);
  }
  return out;
}

}  // namespace driveid
