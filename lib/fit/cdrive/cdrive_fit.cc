#include "fit/cdrive/cdrive_fit.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <stdexcept>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "core/errors.h"
#include "core/name_list.h"
#include "core/option_check.h"
#include "fit/core/linear_regression.h"
#include "logs/csv_log.h"
#include "models/missing_values.h"
#include "signal/local_polynomial.h"

namespace driveid {
namespace {

using CDriveRow = ParameterRow<CDriveSection, CDriveParameters>;

// The rows of the table a fit ("friction" or "inertia") estimates, in table order.
std::vector<const CDriveRow*> FitRows(const char* fit) {
  std::vector<const CDriveRow*> rows;
  for (const auto& row : CDriveParameterTable()) {
    if (row.spec.InFit(fit)) rows.push_back(&row);
  }
  return rows;
}

std::string Key(double CDriveParameters::*member) { return KeyOf(CDriveParameterTable(), member); }

// The regressor columns: every model parameter of the table, then a + b and
// a - b of eq. (17) for a friction fit without the inertias (nuisances).
std::vector<std::string> RegressorColumns() {
  std::vector<std::string> columns;
  for (const auto& row : CDriveParameterTable()) {
    if (row.in_model != nullptr && !row.spec.required) columns.push_back(row.spec.key);  // not p
  }
  columns.push_back("a_plus_b");
  columns.push_back("a_minus_b");
  return columns;
}

// One sample's rows in sum (tau_L + tau_R) and difference (tau_L - tau_R)
// form, in the order of RegressorColumns(): I_h, I_c, m, beta, gamma, delta,
// eta, a + b, a - b.
struct SampleRows {
  std::vector<double> sum, difference;
};

SampleRows CalcSampleRows(double lead, double rate_left, double rate_right, double acceleration_left,
                          double acceleration_right) {
  const double rate_sum = rate_left + rate_right, rate_difference = rate_left - rate_right;
  const double sign_left = Signum(rate_left), sign_right = Signum(rate_right);
  const double acceleration_sum = acceleration_left + acceleration_right;
  const double acceleration_difference = acceleration_left - acceleration_right;
  const double mass_coupling = CalcMassCoupling(lead);
  return {{acceleration_sum, 0.5 * acceleration_sum, 0.0, rate_sum, 0.0, sign_left + sign_right, 0.0, acceleration_sum,
           0.0},
          {acceleration_difference, 0.0, 2.0 * mass_coupling * acceleration_difference, rate_difference, rate_difference,
           sign_left - sign_right, 2.0 * Signum(rate_difference), 0.0, acceleration_difference}};
}

enum class Kind { kFriction, kInertia };

std::string FrictionAdvice(const std::vector<std::string>& involved) {
  const bool motor = Contains(involved, Key(&CDriveParameters::viscous_motor)) ||
                     Contains(involved, Key(&CDriveParameters::coulomb_motor));
  const bool collar = Contains(involved, Key(&CDriveParameters::viscous_collar)) ||
                      Contains(involved, Key(&CDriveParameters::coulomb_collar));
  if (motor && collar) {
    return "pure translation (psi_L' = -psi_R') fixes only beta + gamma and delta + 2 eta: add a rotation or helical "
           "program to separate the motors' friction from the collar's";
  }
  if (collar) {
    return "gamma and eta need motion with psi_L' != psi_R' (translation or helical programs): in pure rotation the "
           "collar does not move on the screws";
  }
  return "add programs with other velocity profiles or fix some coefficients with ‹params›";
}

std::string InertiaAdvice(const std::vector<std::string>& involved) {
  const int count = Contains(involved, Key(&CDriveParameters::hub_inertia)) +
                    Contains(involved, Key(&CDriveParameters::collar_inertia)) +
                    Contains(involved, Key(&CDriveParameters::collar_mass));
  if (count >= 2) {
    return "only a = I_h + I_c/4 + p^2 m/(16 pi^2) and b = I_c/4 - p^2 m/(16 pi^2) are identifiable from motor "
           "torques (a + b from rotation, a - b from translation): fix one of I_h, I_c, m with ‹params›";
  }
  return "";
}

// Which samples may enter the sum and the difference rows. A sample needs
// certain Coulomb signs (|rates| >= min_rate; for the difference also
// |psi_L' - psi_R'|), and so must every sample within its differentiator
// window: around a reversal the drive sticks and breaks away, the motion is
// not smooth, and a local quadratic that straddles it biases the rates and
// accelerations (with closed-loop logs by several percent in gamma).
struct UsableMask {
  std::vector<char> sum, difference;
};

std::vector<char> Erode(const std::vector<double>& time, const std::vector<char>& ok, double half_window) {
  const std::size_t n = time.size();
  std::vector<char> out(n, 0);
  double last_bad = -1e300;
  std::vector<double> since(n), until(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (!ok[k]) last_bad = time[k];
    since[k] = time[k] - last_bad;
  }
  double next_bad = 1e300;
  for (std::size_t k = n; k-- > 0;) {
    if (!ok[k]) next_bad = time[k];
    until[k] = next_bad - time[k];
  }
  for (std::size_t k = 0; k < n; ++k) out[k] = since[k] > half_window && until[k] > half_window;
  return out;
}

UsableMask UsableSamples(const std::vector<double>& time, const SignalDerivatives& left, const SignalDerivatives& right,
                         double min_rate, double half_window, double settle) {
  const std::size_t n = time.size();
  std::vector<char> signs(n), collar(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double rl = left.rate[k], rr = right.rate[k];
    // Samples without a centred window (log ends) do not spoil their neighbours.
    const bool centred = left.valid[k] && right.valid[k];
    signs[k] = !centred || (std::abs(rl) >= min_rate && std::abs(rr) >= min_rate);
    collar[k] = !centred || (signs[k] && std::abs(rl - rr) >= min_rate);
  }
  const double reach = std::max(half_window, settle);
  return {Erode(time, signs, reach), Erode(time, collar, reach)};
}

struct Derivatives {
  std::vector<SignalDerivatives> left, right;  // per log
  int rows_possible = 0;
};


// The fit's parameters: the free members of the fitted group, a + b and
// a - b of eq. (17) as nuisances when the friction fit lacks the inertia;
// every column not free fixed (at its value, the nuisance-replaced inertias
// and the unknown columns at 0); every value the fit needs and the file
// lacks named in one message.
struct CDriveDesign {
  std::vector<const CDriveRow*> table;
  std::vector<int> free_columns;  // index into table
  std::vector<FitParameter> parameters;
  std::vector<std::string> columns = RegressorColumns();
  std::map<std::string, double> fixed;
  bool inertia_nuisance = false;
};

CDriveDesign MakeCDriveDesign(const CDriveSection& start_section, const CDriveParameters& start,
                              const CDriveFitOptions& options, bool friction) {
  CDriveDesign d;
  const char* fit_name = friction ? "friction" : "inertia";
  d.table = FitRows(fit_name);
  std::vector<std::string> free = options.free;
  if (free.empty()) free = FitParameterKeys(CDriveParameterTable(), fit_name, true);
  CheckFreeNames(CDriveParameterTable(), fit_name, free);
  // Everything not free must be known: the inertia for the friction fit, the
  // friction for the inertia fit, and the fixed members of the fitted group.
  // Without I_h, I_c and m the friction fit estimates a + b and a - b of
  // eq. (17) alongside, as nuisance parameters (their columns, the summed and
  // differenced accelerations, are nearly orthogonal to the friction columns).
  d.inertia_nuisance =
      friction && !(start_section.hub_inertia && start_section.collar_inertia && start_section.collar_mass);
  std::vector<const ParameterSpec*> needed;
  if (!start_section.lead) needed.push_back(&SpecOf(CDriveParameterTable(), &CDriveSection::lead));
  for (const auto& row : CDriveParameterTable()) {
    if (row.in_model == nullptr || row.spec.required) continue;  // k_t; p was checked
    if (d.inertia_nuisance && row.spec.InFit("inertia")) continue;
    if (!Contains(free, row.spec.key) && !(start_section.*(row.in_section))) needed.push_back(&row.spec);
  }
  if (!needed.empty()) {
    throw MissingValuesError("‹params›", "cdrive", needed, "(fixed in this fit)", " (or name the fitted ones in ‹free›)");
  }
  for (int j = 0; j < static_cast<int>(d.table.size()); ++j) {
    if (!Contains(free, d.table[j]->spec.key)) continue;
    d.free_columns.push_back(j);
    const double value = start.*(d.table[j]->in_model);
    const double initial = value == value && value > 0.0 ? value : 0.0;
    d.parameters.push_back({d.table[j]->spec.key, initial, 0.0, initial > 0.0 ? initial : d.table[j]->spec.typical});
  }
  if (d.inertia_nuisance) {
    d.parameters.push_back({"a_plus_b", 0.0, 0.0, 1e-3});
    d.parameters.push_back({"a_minus_b", 0.0, 0.0, 1e-3});
  }
  for (const auto& name : d.columns) {
    const auto* row = FindParameter(CDriveParameterTable(), name);
    const bool nuisance_inertia = d.inertia_nuisance && row != nullptr && row->spec.InFit("inertia");
    d.fixed[name] = row == nullptr || nuisance_inertia ? 0.0 : (start_section.*(row->in_section)).value_or(0.0);
  }
  return d;
}

// Rates and accelerations of every log from the +-half_window fit, and the
// samples usable for the sum and difference rows. When a + b and a - b are
// estimated, the accelerations are regressors and their noise would
// attenuate them: take those from a window twice as wide. (When M is known
// the narrow window is better: the subtracted inertial torque must follow
// the closed-loop oscillations after reversals.)
Derivatives DifferentiateCDriveLogs(const std::vector<CDriveLog>& logs, const CDriveFitOptions& options, double settle,
                                    bool wide_accelerations, std::vector<UsableMask>& usable, std::size_t& row_count) {
  Derivatives design;
  row_count = 0;
  for (const auto& log : logs) {
    if (log.time.size() < kMinCDriveLogSamples) {
      throw InputError(fmt::format("{}: {} samples: too few to differentiate", log.path, log.time.size()));
    }
    design.left.push_back(EstimateDerivatives(log.time, log.angle_left, options.half_window));
    design.right.push_back(EstimateDerivatives(log.time, log.angle_right, options.half_window));
    if (wide_accelerations) {
      const double wide = 2.0 * options.half_window;
      const SignalDerivatives wide_left = EstimateDerivatives(log.time, log.angle_left, wide);
      const SignalDerivatives wide_right = EstimateDerivatives(log.time, log.angle_right, wide);
      for (std::size_t k = 0; k < log.time.size(); ++k) {
        design.left.back().acceleration[k] = wide_left.acceleration[k];
        design.right.back().acceleration[k] = wide_right.acceleration[k];
        design.left.back().valid[k] = design.left.back().valid[k] && wide_left.valid[k];
        design.right.back().valid[k] = design.right.back().valid[k] && wide_right.valid[k];
      }
    }
    design.left.back().value = {};  // the smoothed angles are not used
    design.right.back().value = {};
    const auto& left = design.left.back();
    const auto& right = design.right.back();
    usable.push_back(UsableSamples(log.time, left, right, options.min_rate, options.half_window, settle));
    for (std::size_t k = 0; k < log.time.size(); ++k) {
      if (!left.valid[k] || !right.valid[k]) continue;
      ++design.rows_possible;
      row_count += static_cast<std::size_t>(usable.back().sum[k]) + static_cast<std::size_t>(usable.back().difference[k]);
    }
  }
  return design;
}

// Rows: per log the sum rows, then the difference rows. The design holds the
// fitted columns only, in the parameters' order; the fixed columns' part of
// each row is its known part. Arrays no later step needs are released.
void AddCDriveRows(const std::vector<CDriveLog>& logs, const CDriveDesign& d, double lead, bool keep_derivatives,
                   Derivatives& design, std::vector<UsableMask>& usable, LinearRegression& regression) {
  std::vector<std::string> fit_columns;
  std::vector<std::size_t> take;
  for (const auto& parameter : d.parameters) {
    fit_columns.push_back(parameter.name);
    take.push_back(static_cast<std::size_t>(std::find(d.columns.begin(), d.columns.end(), parameter.name) -
                                            d.columns.begin()));
  }
  std::vector<std::pair<std::size_t, double>> fixed_terms;
  for (std::size_t j = 0; j < d.columns.size(); ++j) {
    if (!Contains(fit_columns, d.columns[j]) && d.fixed.at(d.columns[j]) != 0.0) {
      fixed_terms.emplace_back(j, d.fixed.at(d.columns[j]));
    }
  }
  std::vector<double> row(take.size());
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const auto& log = logs[i];
    const auto& left = design.left[i];
    const auto& right = design.right[i];
    for (int part = 0; part < 2; ++part) {
      regression.BeginChannel(log.path + (part == 0 ? ":tau_L+tau_R" : ":tau_L-tau_R"));
      for (std::size_t k = 0; k < log.time.size(); ++k) {
        if (!left.valid[k] || !right.valid[k]) continue;
        if (!(part == 0 ? usable[i].sum[k] : usable[i].difference[k])) continue;
        const SampleRows sample = CalcSampleRows(lead, left.rate[k], right.rate[k], left.acceleration[k], right.acceleration[k]);
        const std::vector<double>& all = part == 0 ? sample.sum : sample.difference;
        for (std::size_t c = 0; c < take.size(); ++c) row[c] = all[take[c]];
        double known = 0.0;
        for (const auto& [j, value] : fixed_terms) known += value * all[j];
        regression.AddRow(row, part == 0 ? log.torque_left[k] + log.torque_right[k] : log.torque_left[k] - log.torque_right[k],
                          known);
      }
    }
    usable[i].difference = {};
    if (!keep_derivatives) design.left[i] = design.right[i] = {};  // only the traces use them further
  }
}

// a and b of eq. (17) with their standard errors: from the nuisances a + b
// and a - b, or (inertia fit) linear in the fitted I_h, I_c, m.
void AddInertiaMatrix(const CDriveDesign& d, const CDriveParameters& fitted, double lead, bool friction,
                      CDriveFitOutput& out) {
  const int p = static_cast<int>(d.parameters.size());
  if (d.inertia_nuisance) {
    // a = ((a + b) + (a - b)) / 2, b = ((a + b) - (a - b)) / 2.
    const std::size_t s_index = d.free_columns.size(), d_index = s_index + 1;
    const double sum = out.fit.estimates[s_index].value, difference = out.fit.estimates[d_index].value;
    const auto cov = [&](std::size_t i, std::size_t j) { return out.fit.covariance[i * static_cast<std::size_t>(p) + j]; };
    const double spread = 0.25 * (cov(s_index, s_index) + cov(d_index, d_index));
    out.derived.push_back({"a", 0.5 * (sum + difference), std::sqrt(std::max(0.0, spread + 0.5 * cov(s_index, d_index))),
                           "kg m^2, M diagonal (eq. 17), fitted as a nuisance"});
    out.derived.push_back({"b", 0.5 * (sum - difference), std::sqrt(std::max(0.0, spread - 0.5 * cov(s_index, d_index))),
                           "kg m^2, M off-diagonal, fitted as a nuisance"});
  }
  if (!friction) {
    const double k = CalcMassCoupling(lead);
    const double gradient_a[3] = {1.0, 0.25, k}, gradient_b[3] = {0.0, 0.25, -k};
    auto propagate = [&](const double* gradient) {
      double variance = 0.0;
      for (int i = 0; i < p; ++i) {
        for (int j = 0; j < p; ++j) {
          variance += gradient[d.free_columns[static_cast<std::size_t>(i)]] *
                      out.fit.covariance[static_cast<std::size_t>(i * p + j)] *
                      gradient[d.free_columns[static_cast<std::size_t>(j)]];
        }
      }
      return std::sqrt(std::max(0.0, variance));
    };
    out.derived.push_back({"a", CalcInertiaDiagonal(fitted), propagate(gradient_a), "kg m^2, M diagonal (eq. 17)"});
    out.derived.push_back({"b", CalcInertiaOffDiagonal(fitted), propagate(gradient_b), "kg m^2, M off-diagonal"});
  }
}

// Measured and model torques per log for --trace/--plot.
void AddCDriveTraces(const std::vector<CDriveLog>& logs, const Derivatives& design,
                     const std::vector<UsableMask>& usable, const CDriveParameters& fitted, bool inertia_nuisance,
                     CDriveFitOutput& out) {
  CDriveParameters fixed_with_fit = fitted;  // for the trace when M was a nuisance
  fixed_with_fit.hub_inertia = fixed_with_fit.collar_inertia = fixed_with_fit.collar_mass = 0.0;
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const auto& log = logs[i];
    CDriveTrace trace;
    for (std::size_t k = 0; k < log.time.size(); ++k) {
      if (!design.left[i].valid[k] || !design.right[i].valid[k]) continue;
      const double rl = design.left[i].rate[k], rr = design.right[i].rate[k];
      const Vector2 acceleration = {design.left[i].acceleration[k], design.right[i].acceleration[k]};
      Vector2 model = CalcCDriveInverseDynamics(inertia_nuisance ? fixed_with_fit : fitted, {rl, rr}, acceleration);
      if (inertia_nuisance) {
        const double a = out.derived[0].value, b = out.derived[1].value;
        model[0] += a * acceleration[0] + b * acceleration[1];
        model[1] += b * acceleration[0] + a * acceleration[1];
      }
      trace.time.push_back(log.time[k]);
      trace.measured_left.push_back(log.torque_left[k]);
      trace.measured_right.push_back(log.torque_right[k]);
      trace.model_left.push_back(model[0]);
      trace.model_right.push_back(model[1]);
      trace.used.push_back(usable[i].sum[k]);
    }
    out.traces.push_back(std::move(trace));
  }
}

CDriveFitOutput Fit(const std::vector<CDriveLog>& logs, const CDriveSection& start_section,
                    const CDriveFitOptions& options, Kind kind) {
  const CDriveParameters start = ModelValuesOrNaN(CDriveParameterTable(), start_section);  // NaN = not given
  if (logs.empty()) throw OptionError("no logs given");
  RequireValid(options);
  const bool friction = kind == Kind::kFriction;
  const double settle = options.settle >= 0.0 ? options.settle : (friction ? 0.1 : 0.0);
  const CDriveDesign d = MakeCDriveDesign(start_section, start, options, friction);
  std::vector<UsableMask> usable;
  std::size_t row_count = 0;
  Derivatives design = DifferentiateCDriveLogs(logs, options, settle, d.inertia_nuisance, usable, row_count);
  std::vector<std::string> fit_columns;
  for (const auto& parameter : d.parameters) fit_columns.push_back(parameter.name);
  std::optional<LinearRegression> regression(std::in_place, fit_columns);
  regression->Reserve(row_count);  // the design is the largest thing held: no regrowth
  AddCDriveRows(logs, d, start.lead, options.traces, design, usable, *regression);
  const int n = static_cast<int>(regression->rows());
  if (n == 0) {
    throw IdentificationError(fmt::format(
        "no usable samples: every sample has a motor rate below ‹min_rate› {} rad/s (or the logs are shorter than the "
        "differentiator window)",
        options.min_rate));
  }
  FitOptions fit_options = options.fit;
  if (!fit_options.advice) fit_options.advice = friction ? FrictionAdvice : InertiaAdvice;
  CDriveFitOutput out;
  out.fit = regression->FitAndRelease(d.parameters, {}, fit_options);
  regression.reset();  // before the traces
  // fit% is of the measured sum/difference, not of the part left after the known terms.
  CDriveParameters fitted = start;
  out.section = start_section;
  for (std::size_t j = 0; j < d.free_columns.size(); ++j) {
    const CDriveRow& row = *d.table[d.free_columns[j]];
    fitted.*(row.in_model) = out.fit.estimates[j].value;
    out.section.*(row.in_section) = out.fit.estimates[j].value;
  }
  out.rows_used = n;
  out.rows_possible = design.rows_possible;
  AddInertiaMatrix(d, fitted, start.lead, friction, out);
  if (options.traces) AddCDriveTraces(logs, design, usable, fitted, d.inertia_nuisance, out);
  return out;
}
}  // namespace



std::vector<CDriveTrace> PredictCDriveTorques(const std::vector<CDriveLog>& logs, const CDriveParameters& params,
                                              const CDriveFitOptions& options) {
  RequireValid(options);
  const double settle = options.settle >= 0.0 ? options.settle : 0.1;
  std::vector<CDriveTrace> traces;
  for (const auto& log : logs) {
    if (log.time.size() < kMinCDriveLogSamples) {
      throw InputError(fmt::format("{}: {} samples: too few to differentiate", log.path, log.time.size()));
    }
    const SignalDerivatives left = EstimateDerivatives(log.time, log.angle_left, options.half_window);
    const SignalDerivatives right = EstimateDerivatives(log.time, log.angle_right, options.half_window);
    const auto usable = UsableSamples(log.time, left, right, options.min_rate, options.half_window, settle);
    CDriveTrace trace;
    for (std::size_t k = 0; k < log.time.size(); ++k) {
      if (!left.valid[k] || !right.valid[k]) continue;
      const Vector2 model = CalcCDriveInverseDynamics(params, {left.rate[k], right.rate[k]},
                                                      {left.acceleration[k], right.acceleration[k]});
      trace.time.push_back(log.time[k]);
      trace.measured_left.push_back(log.torque_left[k]);
      trace.measured_right.push_back(log.torque_right[k]);
      trace.model_left.push_back(model[0]);
      trace.model_right.push_back(model[1]);
      trace.used.push_back(usable.sum[k]);
    }
    traces.push_back(std::move(trace));
  }
  return traces;
}

bool CDriveFitOptions::IsValid(std::string* error) const {
  if (!(half_window > 0.0) || !std::isfinite(half_window)) {
    *error = ViolatedConstraint("‹window›", half_window, "window > 0 s");
  } else if (!(min_rate >= 0.0) || !std::isfinite(min_rate)) {
    *error = ViolatedConstraint("‹min_rate›", min_rate, "min rate >= 0");
  } else {
    return true;
  }
  return false;
}

CDriveFitOutput FitCDriveFriction(const std::vector<CDriveLog>& logs, const CDriveSection& start,
                                  const CDriveFitOptions& options) {
  return Fit(logs, start, options, Kind::kFriction);
}

CDriveFitOutput FitCDriveInertia(const std::vector<CDriveLog>& logs, const CDriveSection& start,
                                 const CDriveFitOptions& options) {
  return Fit(logs, start, options, Kind::kInertia);
}

}  // namespace driveid
