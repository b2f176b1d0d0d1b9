#include "logs/cdrive_log.h"

#include <fmt/format.h>

#include "core/errors.h"
#include "logs/log_input.h"
#include "logs/log_columns.h"

namespace driveid {
namespace {
using L = CDriveLog;
constexpr LogColumn<L> kColumns[] = {
    RequiredColumn<L>("t", &FieldOf<L, &L::time>, "{}"),
    RequiredColumn<L>("psi_L", &FieldOf<L, &L::angle_left>, "{:.10g}"),
    RequiredColumn<L>("psi_R", &FieldOf<L, &L::angle_right>, "{:.10g}"),
    RequiredColumn<L>("tau_L|i_L", &FieldOf<L, &L::torque_left>, "{:.7g}"),
    RequiredColumn<L>("tau_R|i_R", &FieldOf<L, &L::torque_right>, "{:.7g}"),
};
constexpr std::size_t kLeft = LogColumnIndex(kColumns, "tau_L|i_L"), kRight = LogColumnIndex(kColumns, "tau_R|i_R");
static_assert(kLeft < std::size(kColumns) && kRight < std::size(kColumns), "C-drive log columns");
}  // namespace

const std::vector<std::string>& CDriveLogColumns() {
  static const std::vector<std::string> columns = LogColumnRequest(kColumns);
  return columns;
}

CDriveLog ParseCDriveLog(const std::string& path, const std::string& text,
                         const std::map<std::string, std::string>& column_map, double torque_constant) {
  CsvReadOptions options;
  options.column_map = column_map;
  return MakeCDriveLog(ParseCsvLog(path, text, CDriveLogColumns(), options), torque_constant);
}

CDriveLog MakeCDriveLog(CsvLog csv, double torque_constant) {
  const bool left_current = csv.names[kLeft] == "i_L", right_current = csv.names[kRight] == "i_R";
  CDriveLog log = MakeLogFromColumns(kColumns, csv);
  if (left_current != right_current) {
    throw InputError(fmt::format("{}: give both motor torques (tau_L, tau_R) or both currents (i_L, i_R)", log.path));
  }
  if (left_current) {
    if (!(torque_constant > 0.0)) {
      throw InputError(fmt::format("{}: the log has currents i_L, i_R: cdrive.k_t must be given in ‹params›", log.path));
    }
    for (double& v : log.torque_left) v *= torque_constant;
    for (double& v : log.torque_right) v *= torque_constant;
  }
  return log;
}

std::string FormatCDriveLog(const CDriveLog& log, const std::vector<std::string>& comments) {
  return FormatLogColumns(kColumns, log, comments);
}

}  // namespace driveid
