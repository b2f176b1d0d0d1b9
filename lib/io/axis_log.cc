#include "io/axis_log.h"

#include <fmt/format.h>

#include "core/errors.h"
#include "io/csv_log.h"

namespace driveid {

const std::vector<std::string>& AxisLogColumns() {
  static const std::vector<std::string> columns = {"t", "q", "tau|i", "?qd", "?tau_known"};
  return columns;
}

AxisLog ParseAxisLog(const std::string& path, const std::string& text,
                     const std::map<std::string, std::string>& column_map, double torque_constant) {
  CsvReadOptions options;
  options.column_map = column_map;
  return MakeAxisLog(ParseCsvLog(path, text, AxisLogColumns(), options), torque_constant);
}

AxisLog MakeAxisLog(CsvLog csv, double torque_constant) {
  const std::string path = csv.label();
  AxisLog log{path, std::move(csv.columns[0]), std::move(csv.columns[1]), std::move(csv.columns[2]),
              std::move(csv.columns[3])};
  if (csv.names[2] == "i") {
    if (!(torque_constant > 0.0)) {
      throw InputError(fmt::format("{}: the log has a current column 'i': axis.k_t must be given in --params", path));
    }
    for (double& v : log.force) v *= torque_constant;
  }
  // A known torque (a spring, a counterweight, a load cell's other side): the
  // model explains the rest (docs/models.md#axis).
  const std::vector<double>& known = csv.columns[4];
  if (!known.empty()) {
    for (std::size_t k = 0; k < log.force.size() && k < known.size(); ++k) log.force[k] -= known[k];
  }
  return log;
}

std::string FormatAxisLog(const AxisLog& log, const std::vector<std::string>& comments) {
  RequireFiniteColumns({{"t", &log.time}, {"q", &log.position}, {"tau", &log.force}}, log.time);
  std::string out;
  for (const auto& line : comments) out += "# " + line + "\n";
  out += "t,q,tau\n";
  for (std::size_t k = 0; k < log.time.size(); ++k) {
    out += fmt::format("{},{:.10g},{:.7g}\n", log.time[k], log.position[k], log.force[k]);
  }
  return out;
}

}  // namespace driveid
