#include "io/step_log.h"

#include <fmt/format.h>

#include "core/errors.h"
#include "io/csv_log.h"

namespace driveid {

const std::vector<std::string>& StepLogColumns() {
  static const std::vector<std::string> columns = {"t", "tau_motor", "tau_link", "?q_motor", "?q_link"};
  return columns;
}

StepLog ParseStepLog(const std::string& path, const std::string& text,
                     const std::map<std::string, std::string>& column_map) {
  CsvReadOptions options;
  options.column_map = column_map;
  return MakeStepLog(ParseCsvLog(path, text, StepLogColumns(), options));
}

StepLog MakeStepLog(CsvLog csv) {
  const std::string path = csv.label();
  StepLog log;
  log.path = path;
  log.time = std::move(csv.columns[0]);
  log.motor_torque = std::move(csv.columns[1]);
  log.link_torque = std::move(csv.columns[2]);
  log.motor_angle = std::move(csv.columns[3]);
  log.link_angle = std::move(csv.columns[4]);
  return log;
}

std::string FormatStepLog(const StepLog& log, const std::vector<std::string>& comments) {
  RequireFiniteColumns({{"t", &log.time}, {"tau_motor", &log.motor_torque}, {"tau_link", &log.link_torque}}, log.time);
  std::string out;
  for (const auto& line : comments) out += "# " + line + "\n";
  out += "t,tau_motor,tau_link\n";
  for (std::size_t k = 0; k < log.time.size(); ++k) {
    out += fmt::format("{},{},{:.9g}\n", log.time[k], log.motor_torque[k], log.link_torque[k]);
  }
  return out;
}

}  // namespace driveid
