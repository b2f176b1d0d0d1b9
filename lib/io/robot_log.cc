#include "io/robot_log.h"

#include <fmt/format.h>

#include "core/errors.h"
#include "io/csv_log.h"

namespace driveid {

const std::vector<std::string>& RobotLogColumns() {
  static const std::vector<std::string> columns = {"t", "theta1", "theta2", "theta3", "i1", "i2", "i3"};
  return columns;
}

RobotLog ParseRobotLog(const std::string& path, const std::string& text,
                       const std::map<std::string, std::string>& column_map) {
  CsvReadOptions options;
  options.column_map = column_map;
  return MakeRobotLog(ParseCsvLog(path, text, RobotLogColumns(), options));
}

RobotLog MakeRobotLog(CsvLog csv) {
  const std::string path = csv.label();
  RobotLog log;
  log.path = path;
  log.time = std::move(csv.columns[0]);
  log.line_numbers = std::move(csv.line_numbers);
  for (std::size_t i = 0; i < 3; ++i) {
    log.angle[i] = std::move(csv.columns[1 + i]);
    log.current[i] = std::move(csv.columns[4 + i]);
  }
  return log;
}

std::string FormatRobotLog(const RobotLog& log, const std::vector<std::string>& comments) {
  RequireFiniteColumns({{"t", &log.time}, {"theta1", &log.angle[0]}, {"theta2", &log.angle[1]}, {"theta3", &log.angle[2]},
                        {"i1", &log.current[0]}, {"i2", &log.current[1]}, {"i3", &log.current[2]}},
                       log.time);
  std::string out;
  for (const auto& line : comments) out += "# " + line + "\n";
  out += "t,theta1,theta2,theta3,i1,i2,i3\n";
  for (std::size_t k = 0; k < log.time.size(); ++k) {
    out += fmt::format("{},{:.10g},{:.10g},{:.10g},{:.6g},{:.6g},{:.6g}\n", log.time[k], log.angle[0][k],
                       log.angle[1][k], log.angle[2][k], log.current[0][k], log.current[1][k], log.current[2][k]);
  }
  return out;
}

}  // namespace driveid
