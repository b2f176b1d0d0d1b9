#include "workflow/frequency_response_run.h"

#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "report/fit_summary.h"
#include "report/frf_report.h"

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

bool FrfRequest::IsValid(std::string* error) const {
  OptionCheck check(error);
  check.Require(method == "auto" || method == "welch" || method == "periodic",
                "‹method› " + method + ": choose auto, welch or periodic");
  check.Require(band.empty() || band.size() == 2, "‹band›: LO,HI or nothing");
  if (band.size() == 2) {
    check.Require(band[1] > band[0], fmt::format("‹band› {},{}: LO must be below HI", band[0], band[1]));
  }
  return check;
}

FrfOptions MakeFrfOptions(const FrfRequest& r) {
  RequireValid(r);
  FrfOptions options;
  options.estimate.resolution = r.resolution;
  options.estimate.period = r.period;
  options.estimate.method = r.method == "welch"      ? FrequencyMethod::kWelch
                            : r.method == "periodic" ? FrequencyMethod::kPeriodic
                                                     : FrequencyMethod::kAuto;
  options.fit = r.fit;
  options.hold = r.zero_order_hold;
  options.two_mass.free = r.free;
  options.two_mass.link_output = ResponseQuantityFromName(r.link_is, "‹link_is›");
  if (r.band.size() == 2) {
    options.two_mass.band_low = r.band[0];
    options.two_mass.band_high = r.band[1];
  }
  return options;
}

FrfOutputs AssembleFrfOutputs(const ParameterFile& start, const JointSection& section, const FrfResult& result,
                              const FitProvenance& provenance, bool trace, bool plot, bool json) {
  FrfOutputs out;
  const ParameterFile fitted = FrfParameterFile(start, section, result);
  if (result.fit) out.fit = result.fit->fit;
  out.parameter_file = FormatParameterFile(fitted, result.fit ? &out.fit : nullptr, &provenance);
  if (trace) out.trace_csv = FormatFrfCsv(result);
  if (plot) out.panels = MakeBodePanels(result);
  // Without a fit the response's own warnings go the fit's way (stderr, or exit 4 with --strict).
  if (!result.fit) out.fit.warnings = result.warnings;
  if (json) {
    Json j = FrfJson(result);
    if (result.fit) j["fit"] = FitJson(out.fit, provenance);
    out.summary = DumpJson(j);
  } else {
    out.summary = FormatFrfSummary(result);
    if (result.fit) out.summary += FormatFitTable(out.fit, provenance);
  }
  return out;
}

}  // namespace driveid
