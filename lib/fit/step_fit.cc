#include "fit/step_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "fit/point_memo.h"
#include "fit/scaled_cost.h"
#include "io/csv_log.h"
#include "sim/drivetrain_simulator.h"

namespace driveid {

bool StepFitOptions::IsValid(std::string* error) const { return OptionCheck(error).Nested(fit); }
namespace {

// The estimable parameters in enum order (sensitivity order), derived from
// the enum; tests/models/table_indices_test.cc checks it against the table.
std::vector<DriveTrainParameter> AllParameters() {
  std::vector<DriveTrainParameter> all;
  for (int e = 0; e < kDriveTrainParameterCount; ++e) all.push_back(static_cast<DriveTrainParameter>(e));
  return all;
}

bool Contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// Model-specific advice for a non-identifiable set (docs/models.md#drive-train identifiability).
std::string StepAdvice(const std::vector<std::string>& involved) {
  std::vector<std::string> advice;
  const auto key = [](DriveTrainParameter parameter) { return std::string(DriveTrainParameterKey(parameter)); };
  const bool link = Contains(involved, key(DriveTrainParameter::kLinkStiffness));
  const bool gearbox = Contains(involved, key(DriveTrainParameter::kGearboxStiffness));
  if (link && gearbox) {
    advice.push_back("fix k_Tl or k_Tg with ‹params›: only their series combination enters the strain gauge's step "
                     "response; a logged link angle q_link separates them (docs/models.md#drive-train)");
  } else if ((link || gearbox) && (Contains(involved, key(DriveTrainParameter::kMotorInertia)) ||
                                    Contains(involved, key(DriveTrainParameter::kViscousFriction)))) {
    advice.push_back("a step response fixes only Theta_motor/k_eq and d_g/k_eq: fix the stiffness with ‹params›");
  }
  if (Contains(involved, "offset") || Contains(involved, "offset_1")) {
    advice.push_back("a per-log offset needs samples before the step to separate it from tau_c");
  }
  return fmt::format("{}", fmt::join(advice, "; "));
}

// The residual channels of one log: the strain gauge, then (when logged and
// used) the motor encoder q_motor = n_g phi and the link angle q_link = Delta,
// each angle weighted by RMS(tau_link) / RMS(angle) so that all count alike
// and tau_link keeps its unit.
struct StepChannels {
  int first_row = 0;
  double motor_weight = 0.0, link_weight = 0.0;  // 0: channel not used
  std::vector<double> weighted_motor, weighted_link;
};

// Samples simulated per piece when a log is simulated in pieces.
constexpr int kStreamRows = 8192;

class StepResiduals final : public ResidualModel, public BlockResidualModel {
 public:
  StepResiduals(const std::vector<StepLog>& logs, const DriveTrainParameters& start, DriveTrainModel model,
                std::vector<DriveTrainParameter> ode_parameters, bool fit_offsets, bool use_angles,
                const LargeProblemPolicy& large = {})
      : logs_(logs), params_(start), ode_parameters_(ode_parameters), fit_offsets_(fit_offsets),
        simulator_(model, start, std::move(ode_parameters)) {
    for (const auto& log : logs_) {
      StepChannels c;
      c.first_row = rows_;
      const int n = static_cast<int>(log.time.size());
      rows_ += n;
      const double torque_scale = CalcRmsDeviation(log.link_torque);
      // An angle channel is used when asked for, logged and moving.
      const auto weigh = [&](const std::vector<double>& angle, double* weight, std::vector<double>* weighted) {
        const double angle_scale = use_angles ? CalcRmsDeviation(angle) : 0.0;
        if (!(angle_scale > 0.0 && torque_scale > 0.0)) return;
        *weight = torque_scale / angle_scale;
        for (double q : angle) weighted->push_back(q * *weight);
        rows_ += n;
      };
      weigh(log.motor_angle, &c.motor_weight, &c.weighted_motor);
      weigh(log.link_angle, &c.link_weight, &c.weighted_link);
      channels_.push_back(std::move(c));
    }
    const bool angles = std::any_of(channels_.begin(), channels_.end(),
                                    [](const StepChannels& c) { return c.motor_weight > 0.0 || c.link_weight > 0.0; });
    simulator_.set_record_angles(angles);
    // A single tau_link log whose Jacobian is large is simulated in pieces
    // as the solver asks for its rows in order, so that the sensitivities
    // are held once (in the solver's Jacobian), not twice; only the
    // simulated torque of the last point is remembered.
    streaming_ = logs_.size() == 1 && !angles &&
                 large.IsLarge(static_cast<std::size_t>(rows_), static_cast<std::size_t>(parameter_count()));
  }

  int residual_count() const override { return rows_; }
  int parameter_count() const {
    return static_cast<int>(ode_parameters_.size()) + (fit_offsets_ ? static_cast<int>(logs_.size()) : 0);
  }

  bool Evaluate(const double* parameters, double* residuals, double* jacobian) override {
    const std::size_t q = ode_parameters_.size();
    const int p = parameter_count();
    if (streaming_) {
      for (int begin = 0; begin < rows_; begin += kStreamRows) {
        const int end = std::min(rows_, begin + kStreamRows);
        if (!EvaluateRows(parameters, begin, end, residuals + begin,
                          jacobian != nullptr ? jacobian + static_cast<std::size_t>(begin) * static_cast<std::size_t>(p)
                                              : nullptr)) {
          return false;
        }
      }
      return true;
    }
    for (std::size_t i = 0; i < logs_.size(); ++i) {
      const int base = channels_[i].first_row;
      const int offset_column = fit_offsets_ ? static_cast<int>(q + i) : -1;
      if (!EvaluateLog(i, parameters, fit_offsets_ ? parameters[q + i] : 0.0, residuals + base,
                       jacobian != nullptr ? jacobian + static_cast<std::size_t>(base) * static_cast<std::size_t>(p) : nullptr,
                       p, offset_column)) {
        return false;
      }
    }
    return true;
  }

  // BlockResidualModel: a block per log, its offset its own parameter.
  int shared_count() const override { return static_cast<int>(ode_parameters_.size()); }
  int block_count() const override { return static_cast<int>(logs_.size()); }
  int block_rows(int block) const override {
    const std::size_t i = static_cast<std::size_t>(block);
    const int next = i + 1 < channels_.size() ? channels_[i + 1].first_row : rows_;
    return next - channels_[i].first_row;
  }
  int local_count(int) const override { return fit_offsets_ ? 1 : 0; }
  bool EvaluateBlock(int block, const double* shared, const double* local, double* residuals,
                     double* jacobian) override {
    const int q = shared_count();
    return EvaluateLog(static_cast<std::size_t>(block), shared, fit_offsets_ ? local[0] : 0.0, residuals, jacobian,
                       q + local_count(block), fit_offsets_ ? q : -1);
  }

  // Log i's rows: residuals from its first row on, Jacobian rows of `stride`
  // columns (the ODE parameters first, the offset at `offset_column` if >= 0,
  // every other column 0).
  bool EvaluateLog(std::size_t i, const double* ode_values, double offset, double* residuals, double* jacobian,
                   int stride, int offset_column) {
    if (!Simulated(i, ode_values, jacobian != nullptr)) return false;
    const std::size_t n = logs_[i].time.size();
    const std::size_t channels = 1 + (channels_[i].motor_weight > 0.0) + (channels_[i].link_weight > 0.0);
    return FillRows(i, offset, 0, channels * n, residuals, jacobian, static_cast<std::size_t>(stride), offset_column,
                    response_, 0);
  }

  // Row ranges of a single log (the model remembers its last simulation, so
  // Ceres can be given the rows in chunks without a simulation per chunk).
  bool evaluates_rows() const override { return logs_.size() == 1; }
  bool EvaluateRows(const double* parameters, int begin, int end, double* residuals, double* jacobian) override {
    const std::size_t q = ode_parameters_.size();
    const double offset = fit_offsets_ ? parameters[q] : 0.0;
    const std::size_t p = static_cast<std::size_t>(parameter_count());
    const int offset_column = fit_offsets_ ? static_cast<int>(q) : -1;
    const auto first = static_cast<std::size_t>(begin), last = static_cast<std::size_t>(end);
    if (!streaming_) {
      if (!Simulated(0, parameters, jacobian != nullptr)) return false;
      return FillRows(0, offset, first, last, residuals, jacobian, p, offset_column, response_, 0);
    }
    if (!simulated_.Holds(parameters, q)) {
      simulated_.Remember(parameters, q);  // the point of the stream and of memo_ from now on
      simulated_.succeeded = true;
      memo_rows_ = 0;
      streaming_now_ = false;
    }
    if (!simulated_.succeeded) return false;
    if (jacobian == nullptr && last <= memo_rows_) {
      return FillRows(0, offset, first, last, residuals, nullptr, p, offset_column, memo_, 0);
    }
    const bool sensitivities = jacobian != nullptr;
    try {
      if (!(streaming_now_ && simulator_.next_sample() == first && (stream_sensitivities_ || !sensitivities))) {
        for (std::size_t j = 0; j < q; ++j) SetDriveTrainParameter(params_, ode_parameters_[j], parameters[j]);
        streaming_now_ = false;
        simulator_.Start(params_, logs_[0].time, logs_[0].motor_torque, sensitivities);
        streaming_now_ = true;
        stream_sensitivities_ = sensitivities;
      }
      while (simulator_.next_sample() < first) {  // rows asked out of order: simulate up to them
        Remember(simulator_.next_sample(), std::min(first, simulator_.next_sample() + kStreamRows));
      }
      Remember(first, last);
    } catch (const IdentificationError& e) {
      last_failure_ = e.what();  // integrator failure at these values: the solver backs off
      simulated_.succeeded = false;
      streaming_now_ = false;
      return false;
    }
    return FillRows(0, offset, first, last, residuals, jacobian, p, offset_column, response_, first);
  }
  void Release() override {
    simulated_.Forget();
    streaming_now_ = false;
    response_ = DriveTrainResponse{};
    memo_ = DriveTrainResponse{};
    memo_rows_ = 0;
  }

  // Streaming: simulates samples [first, last) into response_ and keeps
  // their torque in memo_ (contiguous from sample 0 on).
  void Remember(std::size_t first, std::size_t last) {
    simulator_.Advance(last - 1, &response_);
    if (first > memo_rows_) return;
    memo_.link_torque.resize(static_cast<std::size_t>(rows_));
    std::copy(response_.link_torque.begin(), response_.link_torque.end(),
              memo_.link_torque.begin() + static_cast<std::ptrdiff_t>(first));
    memo_rows_ = std::max(memo_rows_, last);
  }

  // Simulates log i at the ODE parameter values unless it is the single log's
  // last simulation (with sensitivities if `sensitivities`); false (with
  // last_failure_) if the integrator fails there, remembered as well.
  bool Simulated(std::size_t i, const double* ode_values, bool sensitivities) {
    const std::size_t q = ode_parameters_.size();
    const bool same = logs_.size() == 1 && simulated_.Holds(ode_values, q);
    if (same && !simulated_.succeeded) return false;
    if (same && (!sensitivities || simulated_.with_jacobian)) return true;
    for (std::size_t j = 0; j < q; ++j) SetDriveTrainParameter(params_, ode_parameters_[j], ode_values[j]);
    simulated_.Forget();
    simulated_.with_jacobian = sensitivities;
    simulated_.succeeded = false;
    try {
      simulator_.Simulate(params_, logs_[i].time, logs_[i].motor_torque, sensitivities, &response_);
      simulated_.succeeded = true;
      last_failure_.clear();
    } catch (const IdentificationError& e) {
      last_failure_ = e.what();  // integrator failure at these values: the solver backs off
    }
    simulated_.Remember(ode_values, q);
    return simulated_.succeeded;
  }

  // Rows [begin, end) of log i from the last simulation: residuals[0] is row
  // `begin`. Rows are tau_link at every sample, then q_motor = n_g phi and
  // q_link = Delta where used (weighted; no strain-gauge offset there).
  bool FillRows(std::size_t i, double offset, std::size_t begin, std::size_t end, double* residuals,
                double* jacobian, std::size_t p, int offset_column, const DriveTrainResponse& response,
                std::size_t response_first) {
    const std::size_t q = ode_parameters_.size();
    const StepLog& log = logs_[i];
    const StepChannels& c = channels_[i];
    const std::size_t n = log.time.size();
    const double n_g = params_.gear_ratio;
    struct Channel {
      double weight, scale, offset;
      const std::vector<double>*measured, *model, *sensitivity;
    };
    const Channel channels[] = {
        {1.0, 1.0, offset, &log.link_torque, &response.link_torque, &response.link_torque_sensitivity},
        {c.motor_weight, n_g, 0.0, &log.motor_angle, &response.motor_angle, &response.motor_angle_sensitivity},
        {c.link_weight, 1.0, 0.0, &log.link_angle, &response.deflection, &response.deflection_sensitivity}};
    std::size_t first = 0;  // first row of the channel
    for (const Channel& ch : channels) {
      if (ch.weight == 0.0) continue;
      for (std::size_t row = std::max(begin, first); row < std::min(end, first + n); ++row) {
        const std::size_t k = row - first, at = k - response_first;  // sample; its index in `response`
        const double r = ch.weight * (ch.scale * (*ch.model)[at] + ch.offset - (*ch.measured)[k]);
        if (!std::isfinite(r)) {
          last_failure_ = "the simulated response is not finite";
          return false;
        }
        residuals[row - begin] = r;
        if (jacobian == nullptr) continue;
        double* out = jacobian + (row - begin) * p;
        std::fill(out, out + p, 0.0);
        for (std::size_t j = 0; j < q; ++j) out[j] = ch.weight * ch.scale * (*ch.sensitivity)[at * q + j];
        if (offset_column >= 0 && &ch == &channels[0]) out[offset_column] = 1.0;  // d r / d offset, tau_link only
      }
      first += n;
    }
    return true;
  }

  std::string LastFailure() const override { return last_failure_; }

  std::vector<double> Simulate(std::size_t i, const double* parameters) {
    simulated_.Forget();
    const std::size_t q = ode_parameters_.size();
    for (std::size_t j = 0; j < q; ++j) SetDriveTrainParameter(params_, ode_parameters_[j], parameters[j]);
    simulator_.Simulate(params_, logs_[i].time, logs_[i].motor_torque, false, &response_);
    std::vector<double> out = response_.link_torque;
    if (fit_offsets_) {
      for (double& y : out) y += parameters[q + i];
    }
    return out;
  }

  void set_integration(DriveTrainIntegration integration) { simulator_.set_integration(integration); }

  /// The fit's channels: per log tau_link, then q_motor and q_link where used.
  std::vector<FitChannel> Channels() const {
    std::vector<FitChannel> out;
    for (std::size_t i = 0; i < logs_.size(); ++i) {
      const StepChannels& c = channels_[i];
      const int n = static_cast<int>(logs_[i].time.size());
      int begin = c.first_row;
      out.push_back({logs_[i].path + ":tau_link", begin, n, logs_[i].link_torque.data()});
      if (c.motor_weight > 0.0) out.push_back({logs_[i].path + ":q_motor", begin += n, n, c.weighted_motor.data()});
      if (c.link_weight > 0.0) out.push_back({logs_[i].path + ":q_link", begin += n, n, c.weighted_link.data()});
    }
    return out;
  }
  /// RMSE back in the angle channels' units.
  void UnweightRmse(FitResult& fit) const {
    std::size_t index = 0;
    for (const auto& c : channels_) {
      ++index;
      if (c.motor_weight > 0.0) fit.channels[index++].rmse /= c.motor_weight;
      if (c.link_weight > 0.0) fit.channels[index++].rmse /= c.link_weight;
    }
  }

 private:
  const std::vector<StepLog>& logs_;
  DriveTrainParameters params_;
  std::vector<DriveTrainParameter> ode_parameters_;
  bool fit_offsets_;
  DriveTrainSimulator simulator_;
  DriveTrainResponse response_;
  std::vector<StepChannels> channels_;
  int rows_ = 0;
  std::string last_failure_;
  // The ODE parameter values of response_ (one log), whether that simulation
  // succeeded and has sensitivities (fit/point_memo.h).
  PointMemo simulated_;
  // Streaming (see the constructor): the simulation under way is at
  // simulated_ (with sensitivities if stream_sensitivities_); memo_ holds
  // its torque for samples [0, memo_rows_).
  bool streaming_ = false, streaming_now_ = false, stream_sensitivities_ = false;
  DriveTrainResponse memo_;
  std::size_t memo_rows_ = 0;
};

void CheckStepLog(const StepLog& log) {
  if (log.time.size() < kMinStepLogSamples) {
    throw InputError(fmt::format("{}: {} samples: a step log needs at least {}", log.path, log.time.size(),
                                 kMinStepLogSamples));
  }
  const bool steps = std::any_of(log.motor_torque.begin(), log.motor_torque.end(),
                                 [&](double u) { return u != log.motor_torque.front(); });
  if (!steps && log.motor_torque.front() == 0.0) {
    throw IdentificationError(fmt::format(
        "{}: column 'tau_motor' is zero throughout: the log holds no torque step to identify anything from",
        log.path));
  }
}

}  // namespace

std::unique_ptr<ResidualModel> MakeStepResiduals(const std::vector<StepLog>& logs, const DriveTrainParameters& start,
                                                 DriveTrainModel model, std::vector<DriveTrainParameter> free,
                                                 bool fit_offsets) {
  return std::make_unique<StepResiduals>(logs, start, model, std::move(free), fit_offsets, false);
}



namespace {

// Start of a log's offset from the data: the mean link torque over the
// samples before the motor torque first changes from 0, where the model
// rests at its zero state and predicts exactly 0 (0 without such samples).
// A long log's steady state fixes only offset + tau_c-side terms together;
// started at 0, a fit can settle on another branch (overshoot, then stick
// on the far side) that the short pre-step segment penalises too little.
double PreStepMean(const StepLog& log) {
  double sum = 0.0;
  std::size_t count = 0;
  while (count < log.time.size() && log.motor_torque[count] == 0.0) sum += log.link_torque[count++];
  return count == 0 || count == log.time.size() ? 0.0 : sum / static_cast<double>(count);
}

// Samples in the first transient of a log: up to the second change of the
// motor torque or ten 90 % rise times of the link torque after the first
// change (at least 10 samples), whichever comes first. Its length follows
// the drive's own time scale, read from the data, not the log's length.
std::size_t FirstTransientLength(const StepLog& log) {
  const std::size_t n = log.time.size();
  std::size_t first = 0;
  while (first < n && log.motor_torque[first] == log.motor_torque.front()) ++first;
  if (first == n) first = 0;  // torque held from the start: its transient begins at once
  std::size_t end = first + 1;
  while (end < n && log.motor_torque[end] == log.motor_torque[first]) ++end;
  if (end - first < 20) return n;
  const double before = PreStepMean(log);
  double after = 0.0;
  const std::size_t tail = std::max<std::size_t>(1, (end - first) / 5);
  for (std::size_t k = end - tail; k < end; ++k) after += log.link_torque[k];
  after /= static_cast<double>(tail);
  std::size_t rise = first;
  while (rise < end && std::abs(log.link_torque[rise] - before) < 0.9 * std::abs(after - before)) ++rise;
  const double rise_time = std::max(log.time[rise < end ? rise : end - 1] - log.time[first],
                                    10.0 * (log.time[first + 1] - log.time[first]));
  std::size_t stop = first;
  while (stop < end && log.time[stop] - log.time[first] <= 10.0 * rise_time) ++stop;
  return stop;
}

// The first `length` samples of a log (copied, nothing more).
StepLog Prefix(const StepLog& log, std::size_t length) {
  const auto head = [length](const std::vector<double>& v) {
    return std::vector<double>(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(std::min(length, v.size())));
  };
  return {log.path, head(log.time), head(log.motor_torque), head(log.link_torque), head(log.motor_angle),
          head(log.link_angle)};
}

// One solve from `start` (offsets from `start_offsets`, 0 when empty).
StepFitOutput FitFrom(const std::vector<StepLog>& logs, const DriveTrainParameters& start,
                      const std::vector<double>& start_offsets, DriveTrainModel model,
                      const std::vector<std::string>& free, const FitOptions& options,
                      DriveTrainIntegration integration) {
  std::vector<DriveTrainParameter> ode_parameters;
  std::vector<FitParameter> fit_parameters;
  for (auto parameter : AllParameters()) {
    const std::string key = DriveTrainParameterKey(parameter);
    if (!Contains(free, key)) continue;
    const double value = GetDriveTrainParameter(start, parameter);
    if (!(value > 0.0)) {
      throw InputError(fmt::format("‹free› {}: the starting value in ‹params› must be > 0, got {}", key, value));
    }
    ode_parameters.push_back(parameter);
    // Friction may vanish; inertias and stiffnesses must stay strictly positive.
    const bool may_vanish = parameter == DriveTrainParameter::kViscousFriction ||
                            parameter == DriveTrainParameter::kCoulombFriction;
    fit_parameters.push_back({key, value, may_vanish ? 0.0 : 1e-6 * value, 0.0});
  }
  const bool fit_offsets = Contains(free, "offset");
  if (fit_offsets) {
    double scale = 0.0;
    for (const auto& log : logs) {
      for (double y : log.link_torque) scale = std::max(scale, std::abs(y));
    }
    for (std::size_t i = 0; i < logs.size(); ++i) {
      const double initial = i < start_offsets.size() ? start_offsets[i] : PreStepMean(logs[i]);
      fit_parameters.push_back({fmt::format("offset_{}", i + 1), initial, -std::numeric_limits<double>::infinity(),
                                std::max(1e-3 * scale, 1e-9)});
    }
  }

  StepResiduals residuals(logs, start, model, ode_parameters, fit_offsets, true, options.large);
  residuals.set_integration(integration);
  const std::vector<FitChannel> channels = residuals.Channels();
  FitOptions fit_options = options;
  if (!fit_options.advice) fit_options.advice = StepAdvice;

  StepFitOutput output;
  // Several logs with offsets: a block per log, the offsets eliminated by
  // the Schur complement (time and memory linear in the number of logs).
  output.fit = fit_offsets && logs.size() > 1
                   ? FitBlockLeastSquares(residuals, fit_parameters, channels, fit_options)
                   : FitLeastSquares(residuals, fit_parameters, channels, fit_options);
  residuals.UnweightRmse(output.fit);
  std::vector<double> estimate;
  for (const auto& e : output.fit.estimates) estimate.push_back(e.value);
  output.params = start;
  for (std::size_t j = 0; j < ode_parameters.size(); ++j) SetDriveTrainParameter(output.params, ode_parameters[j], estimate[j]);
  output.offsets.assign(logs.size(), 0.0);
  for (std::size_t i = 0; i < logs.size(); ++i) {
    if (fit_offsets) output.offsets[i] = estimate[ode_parameters.size() + i];
    output.simulated.push_back(residuals.Simulate(i, estimate.data()));
  }
  return output;
}

// The parameters of the full model's fit that the reduced model determines
// as well (it has no Theta_g, and k_Tl, k_Tg enter it only as k_eq).
std::vector<std::string> ReducedStageFree(const std::vector<std::string>& free) {
  std::vector<std::string> out;
  for (const auto& key : free) {
    if (key == DriveTrainParameterKey(DriveTrainParameter::kGearboxInertia) ||
        key == DriveTrainParameterKey(DriveTrainParameter::kLinkStiffness) ||
        key == DriveTrainParameterKey(DriveTrainParameter::kGearboxStiffness)) {
      continue;
    }
    out.push_back(key);
  }
  return out;
}

std::string DescribeOptimum(const StepFitOutput& o) {
  std::vector<std::string> parts;
  for (const auto& e : o.fit.estimates) {
    if (parts.size() == 4) {
      parts.push_back("...");
      break;
    }
    parts.push_back(fmt::format("{} {:.4g}", e.name, e.value));
  }
  return fmt::format("cost {:.6g}: {}", o.fit.cost, fmt::join(parts, ", "));
}

// Do two optima differ by more than their statistics allow (any estimate
// further apart than 3 of the kept fit's standard errors, or the cost by
// more than 0.1 %)?
bool Disagree(const StepFitOutput& kept, const StepFitOutput& other) {
  if (std::abs(other.fit.cost - kept.fit.cost) > 1e-3 * kept.fit.cost) return true;
  for (std::size_t j = 0; j < kept.fit.estimates.size(); ++j) {
    const auto& a = kept.fit.estimates[j];
    const double difference = std::abs(a.value - other.fit.estimates[j].value);
    if (difference > 3.0 * a.standard_error + 1e-9 * std::abs(a.value)) return true;
  }
  return false;
}

}  // namespace

namespace {

// The staged start (see FitStepResponses): the reduced model on each log's
// first transient, then (full model) the full model on the same transients,
// then the model on the whole logs. `transient_fit` is the last stage on the
// transients; a failure is kept in `failure`.
struct StagedFit {
  std::optional<StepFitOutput> fit, transient_fit;
  std::string failure;
};

StagedFit FitStaged(const std::vector<StepLog>& logs, const std::vector<std::size_t>& transient_lengths,
                    const DriveTrainParameters& start, const StepFitOptions& options) {
  StagedFit out;
  const bool full = options.model == DriveTrainModel::kFull;
  const std::vector<std::string> reduced_free = full ? ReducedStageFree(options.free) : options.free;
  if (reduced_free.empty()) return out;
  try {
    FitOptions quiet = options.fit;
    quiet.progress = nullptr;
    StepFitOutput stage;
    {
      // The transients live only as long as their fits.
      std::vector<StepLog> transients;
      for (std::size_t i = 0; i < logs.size(); ++i) transients.push_back(Prefix(logs[i], transient_lengths[i]));
      stage = FitFrom(transients, start, {}, DriveTrainModel::kReduced, reduced_free, quiet, options.integration);
      if (full) {
        const int reduced_iterations = stage.fit.iterations;
        stage = FitFrom(transients, stage.params, stage.offsets, options.model, options.free, quiet,
                        options.integration);
        stage.fit.iterations += reduced_iterations;
      }
    }
    out.fit = FitFrom(logs, stage.params, stage.offsets, options.model, options.free, options.fit,
                      options.integration);
    out.fit->fit.iterations += stage.fit.iterations;  // the whole path
    out.transient_fit = std::move(stage);
  } catch (const IdentificationError& e) {
    out.failure = e.what();
  }
  return out;
}

// Does the rest of the log pull the estimates away from what the first
// transients alone say (by more than 3 of their standard errors)?
void WarnIfTransientsMoved(const StepFitOutput& transient_fit, StepFitOutput& staged) {
  std::vector<std::string> moved;
  for (std::size_t j = 0; j < staged.fit.estimates.size() && j < transient_fit.fit.estimates.size(); ++j) {
    const auto& a = transient_fit.fit.estimates[j];
    const auto& b = staged.fit.estimates[j];
    if (a.name == b.name && std::abs(b.value - a.value) > 3.0 * a.standard_error) {
      moved.push_back(fmt::format("{} {:.4g} +- {:.2g} -> {:.4g}", a.name, a.value, a.standard_error, b.value));
    }
  }
  if (!moved.empty()) {
    staged.fit.warnings.push_back(fmt::format(
        "the whole logs pull the estimates away from the first transients' ({}): the model may miss something "
        "over the long run, or the cost has several optima (check with ‹starts› both; docs/models.md#drive-train)",
        fmt::join(moved, ", ")));
  }
}

// Of the staged and the given start's fits, the lower cost, with a warning
// when they disagree.
StepFitOutput KeepLowerCost(StepFitOutput staged, StepFitOutput given) {
  const bool staged_better = staged.fit.cost <= given.fit.cost;
  StepFitOutput kept = staged_better ? std::move(staged) : std::move(given);
  const StepFitOutput& other = staged_better ? given : staged;
  if (Disagree(kept, other)) {
    kept.fit.warnings.push_back(fmt::format(
        "starts disagree: from {} {}; from {} {}; kept the lower cost", staged_better ? "the staged start" : "the given start",
        DescribeOptimum(kept), staged_better ? "the given start" : "the staged start", DescribeOptimum(other)));
  }
  return kept;
}

}  // namespace

StepFitOutput FitStepResponses(const std::vector<StepLog>& logs, const DriveTrainParameters& start,
                               const StepFitOptions& options) {
  RequireValid(options);
  if (logs.empty()) throw OptionError("no step logs given");
  CheckFreeNames(DriveTrainParameterTable(), "step", options.free, {"offset"});
  for (const auto& log : logs) CheckStepLog(log);
  if (options.model == DriveTrainModel::kFull && !(start.gearbox_inertia > 0.0)) {
    throw InputError("the full model needs drivetrain.Theta_g > 0 in ‹params›");
  }
  if (options.model == DriveTrainModel::kReduced &&
      Contains(options.free, DriveTrainParameterKey(DriveTrainParameter::kGearboxInertia))) {
    throw IdentificationError("Theta_g has no effect in the reduced model (it sets Theta_g = 0): use ‹model› full");
  }
  if (options.starts == StepStarts::kGiven) {
    return FitFrom(logs, start, {}, options.model, options.free, options.fit, options.integration);
  }

  // Long logs (docs/models.md#drive-train, "Starting on long logs"): once
  // the drive sticks, the rest of the log weighs the stuck level, which
  // moves in jumps with tau_c and the dynamics (another reversal before
  // sticking), and the full model's undamped link mode rings on with a phase
  // set by the sticking instant; the cost then has neighbouring optima a few
  // times off the truth (reduced, 2 s at 100 kHz: d_g 0.007 for 0.016; full,
  // 2 s at 5 kHz: tau_c near 1, offset near 5 for 5 and 1.3). The staged
  // start: the reduced model (no ringing) fitted to each log's first
  // transient, then (full model) the full model on the same transients,
  // then the model on the whole logs. The fit also runs from the given
  // start; the lower cost wins and a disagreement is reported.
  std::vector<std::size_t> transient_lengths;
  bool shorter = false;
  for (const auto& log : logs) {
    transient_lengths.push_back(FirstTransientLength(log));
    shorter = shorter || transient_lengths.back() < log.time.size();
  }
  if (options.model != DriveTrainModel::kFull && !shorter) {
    return FitFrom(logs, start, {}, options.model, options.free, options.fit, options.integration);
  }
  StagedFit staged = FitStaged(logs, transient_lengths, start, options);
  if (staged.fit && options.starts == StepStarts::kStaged) {
    if (staged.transient_fit) WarnIfTransientsMoved(*staged.transient_fit, *staged.fit);
    return std::move(*staged.fit);
  }
  std::optional<StepFitOutput> given;
  std::string given_failure;
  try {
    given = FitFrom(logs, start, {}, options.model, options.free, options.fit, options.integration);
  } catch (const IdentificationError& e) {
    if (!staged.fit) throw;
    given_failure = e.what();
  }
  if (!staged.fit) {
    if (!staged.failure.empty()) {
      given->fit.warnings.push_back("the staged start failed (" + staged.failure +
                                    "); the fit ran from the given start only");
    }
    return std::move(*given);
  }
  if (!given) {
    staged.fit->fit.warnings.push_back("from the given start the fit failed (" + given_failure +
                                       "); kept the fit from the staged start");
    return std::move(*staged.fit);
  }
  return KeepLowerCost(std::move(*staged.fit), std::move(*given));
}

}  // namespace driveid
