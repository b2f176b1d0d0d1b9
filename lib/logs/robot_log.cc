#include "logs/robot_log.h"

#include <fmt/format.h>

#include "core/errors.h"
#include "logs/log_input.h"
#include "logs/log_columns.h"

namespace driveid {
namespace {
using L = RobotLog;
template <std::size_t I>
std::vector<double>& Angle(L& log) {
  return log.angle[I];
}
template <std::size_t I>
std::vector<double>& Current(L& log) {
  return log.current[I];
}
constexpr LogColumn<L> kColumns[] = {
    RequiredColumn<L>("t", &FieldOf<L, &L::time>, "{}"),
    RequiredColumn<L>("theta1", &Angle<0>, "{:.10g}"),
    RequiredColumn<L>("theta2", &Angle<1>, "{:.10g}"),
    RequiredColumn<L>("theta3", &Angle<2>, "{:.10g}"),
    RequiredColumn<L>("i1", &Current<0>, "{:.6g}"),
    RequiredColumn<L>("i2", &Current<1>, "{:.6g}"),
    RequiredColumn<L>("i3", &Current<2>, "{:.6g}"),
};
}  // namespace

const std::vector<std::string>& RobotLogColumns() {
  static const std::vector<std::string> columns = LogColumnRequest(kColumns);
  return columns;
}

RobotLog ParseRobotLog(const std::string& path, const std::string& text,
                       const std::map<std::string, std::string>& column_map) {
  CsvReadOptions options;
  options.column_map = column_map;
  return MakeRobotLog(ParseCsvLog(path, text, RobotLogColumns(), options));
}

RobotLog MakeRobotLog(CsvLog csv) {
  RobotLog log = MakeLogFromColumns(kColumns, csv);
  log.line_numbers = std::move(csv.line_numbers);
  return log;
}

std::string FormatRobotLog(const RobotLog& log, const std::vector<std::string>& comments) {
  return FormatLogColumns(kColumns, log, comments);
}

}  // namespace driveid
