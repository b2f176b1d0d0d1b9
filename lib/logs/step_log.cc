#include "logs/step_log.h"

#include "logs/log_input.h"
#include "logs/log_columns.h"

namespace driveid {
namespace {
using L = StepLog;
constexpr LogColumn<L> kColumns[] = {
    RequiredColumn<L>("t", &FieldOf<L, &L::time>, "{}"),
    RequiredColumn<L>("tau_motor", &FieldOf<L, &L::motor_torque>, "{}"),
    RequiredColumn<L>("tau_link", &FieldOf<L, &L::link_torque>, "{:.9g}"),
    OptionalColumn<L>("q_motor", &FieldOf<L, &L::motor_angle>),
    OptionalColumn<L>("q_link", &FieldOf<L, &L::link_angle>),
};
}  // namespace

const std::vector<std::string>& StepLogColumns() {
  static const std::vector<std::string> columns = LogColumnRequest(kColumns);
  return columns;
}

StepLog ParseStepLog(const std::string& path, const std::string& text,
                     const std::map<std::string, std::string>& column_map) {
  CsvReadOptions options;
  options.column_map = column_map;
  return MakeStepLog(ParseCsvLog(path, text, StepLogColumns(), options));
}

StepLog MakeStepLog(CsvLog csv) { return MakeLogFromColumns(kColumns, csv); }

std::string FormatStepLog(const StepLog& log, const std::vector<std::string>& comments) {
  return FormatLogColumns(kColumns, log, comments);
}

}  // namespace driveid
