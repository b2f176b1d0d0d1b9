#include "logs/axis_log.h"

#include <fmt/format.h>

#include "core/errors.h"
#include "logs/log_input.h"
#include "logs/log_columns.h"

namespace driveid {
namespace {
using L = AxisLog;
constexpr LogColumn<L> kColumns[] = {
    RequiredColumn<L>("t", &FieldOf<L, &L::time>, "{}"),
    RequiredColumn<L>("q", &FieldOf<L, &L::position>, "{:.10g}"),
    RequiredColumn<L>("tau|i", &FieldOf<L, &L::force>, "{:.7g}"),
    OptionalColumn<L>("qd", &FieldOf<L, &L::rate>),
    OptionalColumn<L>("tau_known", nullptr),  // subtracted from the force (MakeAxisLog)
};
constexpr std::size_t kForce = LogColumnIndex(kColumns, "tau|i");
constexpr std::size_t kKnown = LogColumnIndex(kColumns, "tau_known");
static_assert(kForce < std::size(kColumns) && kKnown < std::size(kColumns), "axis log columns");
}  // namespace

const std::vector<std::string>& AxisLogColumns() {
  static const std::vector<std::string> columns = LogColumnRequest(kColumns);
  return columns;
}

AxisLog ParseAxisLog(const std::string& path, const std::string& text,
                     const std::map<std::string, std::string>& column_map, double torque_constant) {
  CsvReadOptions options;
  options.column_map = column_map;
  return MakeAxisLog(ParseCsvLog(path, text, AxisLogColumns(), options), torque_constant);
}

AxisLog MakeAxisLog(CsvLog csv, double torque_constant) {
  const bool current = csv.names[kForce] == "i";
  const std::vector<double> known = std::move(csv.columns[kKnown]);
  AxisLog log = MakeLogFromColumns(kColumns, csv);
  if (current) {
    if (!(torque_constant > 0.0)) {
      throw InputError(fmt::format("{}: the log has a current column 'i': axis.k_t must be given in ‹params›", log.path));
    }
    for (double& v : log.force) v *= torque_constant;
  }
  // A known torque (a spring, a counterweight, a load cell's other side): the
  // model explains the rest (docs/models.md#axis).
  for (std::size_t k = 0; k < log.force.size() && k < known.size(); ++k) log.force[k] -= known[k];
  return log;
}

std::string FormatAxisLog(const AxisLog& log, const std::vector<std::string>& comments) {
  return FormatLogColumns(kColumns, log, comments);
}

}  // namespace driveid
