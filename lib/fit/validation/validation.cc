#include "fit/validation/validation.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/fit_result.h"
#include "fit/core/adequacy.h"
#include "fit/axis/axis_oe_fit.h"
#include "fit/axis/axis_rows.h"
#include "fit/core/least_squares.h"
#include "fit/core/linear_regression.h"
#include "fit/step/step_fit.h"
#include "models/axis_term.h"
#include "sim/axis_simulator.h"

namespace driveid {
namespace {

std::map<std::string, double> AxisColumnValues(const AxisParameters& params) {
  std::map<std::string, double> values;
  for (const auto& row : AxisParameterTable()) {
    if (row.is_model()) values[row.spec.key] = ModelValue(row, params);
  }
  values[kAxisAbsRateColumn] = 0.0;
  values[kAxisTimeColumn] = 0.0;
  return values;
}

// Minimum |q'| kept, as a fraction of the largest (the fit's default).
constexpr double kMinRateFraction = 0.01;

}  // namespace

std::vector<ValidatedLog> ValidateAxis(const std::vector<AxisLog>& logs, const AxisParameters& params, double cutoff,
                                       int decimation, AxisTorqueTiming timing, AxisReach reach, double torque_delay) {
  const AxisValues values = AxisValuesOf(params);
  for (const AxisTerm* term : AxisTerms()) {
    if (!term->linear() && term->Present(&values[AxisFirstIndex(*term)])) {
      throw InputError(fmt::format("axis.{} is not 0: the inverse-dynamics prediction has no {} term (an output-error "
                                   "validation is not built)",
                                   term->Rows().front().spec.key, term->name()));
    }
  }
  const AxisRows rows =
      BuildAxisRows(logs, cutoff, decimation, kMinRateFraction, AxisRowColumnNames(), timing, reach, torque_delay);
  const std::vector<double> model = rows.regression.Predict(AxisColumnValues(params));
  std::vector<ValidatedLog> out(logs.size());
  for (std::size_t r = 0; r < model.size(); ++r) {
    ValidatedLog& log = out[static_cast<std::size_t>(rows.log_index[r])];
    log.time.push_back(rows.time[r]);
    log.measured.push_back(rows.measured[r]);
    log.model.push_back(model[r]);
  }
  for (std::size_t i = 0; i < logs.size(); ++i) {
    std::vector<double> residuals(out[i].measured.size());
    for (std::size_t k = 0; k < residuals.size(); ++k) residuals[k] = out[i].measured[k] - out[i].model[k];
    out[i].stats = DescribeResiduals(logs[i].path + kTorqueChannelSuffix, out[i].measured.data(), residuals.data(),
                                     static_cast<int>(residuals.size()));
  }
  return out;
}

void RequireValidated(const std::vector<ValidatedLog>& logs) {
  if (logs.empty()) throw IdentificationError("no logs to validate");
  for (const auto& log : logs) {
    if (log.stats.samples == 0) {
      throw IdentificationError(fmt::format("{}: no usable samples to compare (check ‹min_rate›, ‹window›, ‹from›/‹to›)",
                                            log.stats.name));
    }
    // A simulation starts at the log's first state: fewer samples compare
    // nothing it predicted (rmse 0 from one sample).
    if (log.stats.samples < kMinValidatedSamples) {
      throw IdentificationError(fmt::format("{}: {} sample{} to compare, at least {} are needed (a simulation starts "
                                            "at the first)",
                                            log.stats.name, log.stats.samples, log.stats.samples == 1 ? "" : "s",
                                            kMinValidatedSamples));
    }
    if (!std::isfinite(log.stats.rmse) || !std::isfinite(log.stats.autocorrelation)) {
      const auto [low, high] = std::minmax_element(log.measured.begin(), log.measured.end());
      const auto [model_low, model_high] = std::minmax_element(log.model.begin(), log.model.end());
      throw IdentificationError(fmt::format("{}: rmse {}: not finite (measured {:.4g} .. {:.4g}, predicted {:.4g} .. "
                                            "{:.4g}): the numbers overflow double precision",
                                            log.stats.name, log.stats.rmse, *low, *high, *model_low, *model_high));
    }
  }
}

double ChooseAxisValidationCutoff(const std::vector<AxisLog>& logs, const AxisParameters& params, int decimation,
                                  AxisTorqueTiming timing, double torque_delay) {
  return PickAxisCutoff(AxisCutoffCandidates(logs, decimation), [&](double cutoff) {
    double ssr = 0.0;
    int count = 0;
    for (const auto& log : ValidateAxis(logs, params, cutoff, decimation, timing, AxisReach::kAtBand, torque_delay)) {
      ssr += log.stats.rmse * log.stats.rmse * log.stats.samples;
      count += log.stats.samples;
    }
    return count > 0 ? ssr / count : HUGE_VAL;
  });
}

std::vector<ValidatedLog> ValidateCDrive(const std::vector<CDriveLog>& logs, const CDriveParameters& params,
                                         const CDriveFitOptions& options) {
  const std::vector<CDriveTrace> traces = PredictCDriveTorques(logs, params, options);
  std::vector<ValidatedLog> out;
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const CDriveTrace& trace = traces[i];
    for (const bool left : {true, false}) {
      ValidatedLog v;
      std::vector<double> residuals;
      for (std::size_t k = 0; k < trace.time.size(); ++k) {
        if (!trace.used[k]) continue;
        v.time.push_back(trace.time[k]);
        v.measured.push_back(left ? trace.measured_left[k] : trace.measured_right[k]);
        v.model.push_back(left ? trace.model_left[k] : trace.model_right[k]);
        residuals.push_back(v.measured.back() - v.model.back());
      }
      v.stats = DescribeResiduals(logs[i].path + (left ? ":tau_L" : ":tau_R"), v.measured.data(), residuals.data(),
                                  static_cast<int>(residuals.size()));
      out.push_back(std::move(v));
    }
  }
  return out;
}

namespace {

ValidatedLog AngleValidation(const std::string& name, const std::vector<double>& time,
                             const std::vector<double>& measured, std::vector<double> simulated) {
  ValidatedLog v;
  v.time = time;
  v.measured = measured;
  std::vector<double> measured_minus_model(time.size());
  for (std::size_t k = 0; k < time.size(); ++k) measured_minus_model[k] = measured[k] - simulated[k];
  v.model = std::move(simulated);
  v.stats = DescribeResiduals(name, v.measured.data(), measured_minus_model.data(), static_cast<int>(time.size()));
  return v;
}

ValidatedLog PositionValidation(const AxisLog& log, std::vector<double> simulated) {
  return AngleValidation(log.path + ":q", log.time, log.position, std::move(simulated));
}

}  // namespace

std::vector<ValidatedLog> ValidateAxisBySimulation(const std::vector<AxisLog>& logs, const AxisParameters& params) {
  if (!(params.inertia > 0.0)) {
    throw InputError(fmt::format("axis.inertia = {:g}: the simulation needs an inertia > 0", params.inertia));
  }
  std::vector<ValidatedLog> out;
  for (const AxisLog& log : logs) {
    const AxisStart start = AxisLogStart(log);
    const double scale = std::max(CalcRmsDeviation(log.position), 1e-12);
    const double duration = std::max(log.time.back() - log.time.front(), 1e-9);
    AxisSimulator simulator({}, 1e-8 * scale, 1e-8 * scale / duration);
    AxisResponse response;
    simulator.Simulate(params, log.time, log.force, start.position, start.rate, false, &response);
    out.push_back(PositionValidation(log, std::move(response.position)));
  }
  return out;
}

std::vector<ValidatedLog> ValidateMujocoAxis(const std::vector<AxisLog>& logs, const std::string& mjcf,
                                             const MujocoAxisOptions& options) {
  std::vector<ValidatedLog> out;
  for (const AxisLog& log : logs) {
    const AxisStart start = AxisLogStart(log);
    MujocoAxisResponse response = SimulateMujocoAxis(mjcf, options, log.time, log.force, start.position, start.rate);
    out.push_back(PositionValidation(log, std::move(response.position)));
  }
  return out;
}

std::vector<ValidatedLog> ValidateMujocoJoint(const std::vector<JointLog>& logs, const std::string& mjcf,
                                              const std::string& joint, double max_step) {
  std::vector<ValidatedLog> out;
  for (const JointLog& log : logs) {
    if (log.torque.empty()) {
      throw InputError(fmt::format("{}: no motor torque (tau, or i with joint.k_t): nothing drives the joint", log.path));
    }
    MujocoRun run;
    run.drive = joint + "_motor";
    run.max_step = max_step;
    const double motor_rate = CalcLoggedStartRate(log.time, log.motor_position, log.motor_rate);
    const double link_rate = CalcLoggedStartRate(log.time, log.link_position, log.link_rate);
    run.record = {{joint + "_motor", log.motor_position.front(), motor_rate, true},
                  {joint, log.link_position.front(), link_rate, false}};
    MujocoRunResponse response = SimulateMujoco(mjcf, run, log.time, log.torque);
    out.push_back(AngleValidation(log.path + ":q_motor", log.time, log.motor_position, std::move(response.position[0])));
    out.push_back(AngleValidation(log.path + ":q_link", log.time, log.link_position, std::move(response.position[1])));
  }
  return out;
}

std::vector<ValidatedLog> ValidateSteps(const std::vector<StepLog>& logs, const DriveTrainParameters& params,
                                        DriveTrainModel model) {
  const auto residual_model = MakeStepResiduals(logs, params, model, {}, false);
  std::vector<double> residuals(static_cast<std::size_t>(residual_model->residual_count()));
  if (!residual_model->Evaluate(nullptr, residuals.data(), nullptr)) {
    throw IdentificationError("the drive train cannot be simulated with these parameters: " +
                              residual_model->LastFailure());
  }
  std::vector<ValidatedLog> out;
  std::size_t base = 0;
  for (const auto& log : logs) {
    ValidatedLog v;
    v.time = log.time;
    v.measured = log.link_torque;
    std::vector<double> measured_minus_model(log.time.size());
    for (std::size_t k = 0; k < log.time.size(); ++k) {
      // The residual model gives simulated - measured.
      v.model.push_back(log.link_torque[k] + residuals[base + k]);
      measured_minus_model[k] = -residuals[base + k];
    }
    v.stats = DescribeResiduals(log.path + ":tau_link", v.measured.data(), measured_minus_model.data(),
                                static_cast<int>(log.time.size()));
    base += log.time.size();
    out.push_back(std::move(v));
  }
  return out;
}

}  // namespace driveid
