#include "workflow/frequency_response_run.h"

#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {

ResponseQuantity ResponseQuantityFromName(const std::string& name, const std::string& option) {
  if (name == "position") return ResponseQuantity::kPosition;
  if (name == "rate") return ResponseQuantity::kRate;
  if (name == "acceleration") return ResponseQuantity::kAcceleration;
  throw OptionError(fmt::format("{} {}: position, rate or acceleration", option, name));
}

std::string ResponseQuantityOfSignal(const std::string& expression) {
  if (expression.rfind("qd", 0) == 0) return "rate";
  if (expression.rfind("q", 0) == 0) return "position";
  return "";
}

MeasuredResponse MeasuredResponseInSi(MeasuredResponse m, const MeasuredResponseUnits& units) {
  for (double& f : m.frequency) f /= units.radians_per_second ? 2.0 * M_PI : 1.0;
  if (units.decibel) {
    for (double& v : m.magnitude) v = std::pow(10.0, v / 20.0);
  }
  if (units.degrees) {
    for (double& v : m.phase) v *= M_PI / 180.0;
  }
  return m;
}

FrfSignals FrfSignalsFromLog(CsvLog csv, double torque_constant, bool has_reference, bool has_link) {
  FrfSignals s;
  s.label = csv.label();
  s.time = csv.columns[0];
  s.input = csv.columns[1];
  if (csv.names[1] == "i") {
    if (!(torque_constant > 0.0)) {
      throw InputError(fmt::format("{}: a log of current i needs joint.k_t in ‹params›", s.label));
    }
    for (double& v : s.input) v *= torque_constant;
  }
  s.output = csv.columns[2];
  if (has_reference) s.reference = csv.columns[3];
  if (has_link) s.link = csv.columns.back();
  return s;
}

ParameterFile FrfParameterFile(const ParameterFile& start, const JointSection& section, const FrfResult& result) {
  ParameterFile fitted = start;
  if (result.fit) {
    JointSection out_section = section;
    if (!out_section.gear_ratio) out_section.gear_ratio = 1.0;
    StoreModelParameters(JointParameterTable(), result.fit->params, out_section);
    fitted.Set(out_section);
  }
  fitted.Set(result.Section());
  return fitted;
}

}  // namespace driveid
