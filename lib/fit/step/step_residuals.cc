#include "fit/step/step_residuals.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "core/errors.h"
#include "fit/core/fit_statistics.h"
#include "fit/core/point_memo.h"
#include "fit/core/scaled_cost.h"

namespace driveid {
namespace {

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

class StepResiduals final : public StepFitResiduals {
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

  std::vector<double> Simulate(std::size_t i, const double* parameters) override {
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

  void set_integration(DriveTrainIntegration integration) override { simulator_.set_integration(integration); }

  /// The fit's channels: per log tau_link, then q_motor and q_link where used.
  std::vector<FitChannel> Channels() const override {
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
  void UnweightRmse(FitResult& fit) const override {
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
  // succeeded and has sensitivities (fit/core/point_memo.h).
  PointMemo simulated_;
  // Streaming (see the constructor): the simulation under way is at
  // simulated_ (with sensitivities if stream_sensitivities_); memo_ holds
  // its torque for samples [0, memo_rows_).
  bool streaming_ = false, streaming_now_ = false, stream_sensitivities_ = false;
  DriveTrainResponse memo_;
  std::size_t memo_rows_ = 0;
};

}  // namespace

std::unique_ptr<ResidualModel> MakeStepResiduals(const std::vector<StepLog>& logs, const DriveTrainParameters& start,
                                                 DriveTrainModel model, std::vector<DriveTrainParameter> free,
                                                 bool fit_offsets) {
  return std::make_unique<StepResiduals>(logs, start, model, std::move(free), fit_offsets, false);
}

std::unique_ptr<StepFitResiduals> MakeStepFitResiduals(const std::vector<StepLog>& logs,
                                                       const DriveTrainParameters& start, DriveTrainModel model,
                                                       std::vector<DriveTrainParameter> ode_parameters,
                                                       bool fit_offsets, const LargeProblemPolicy& large) {
  return std::make_unique<StepResiduals>(logs, start, model, std::move(ode_parameters), fit_offsets, true, large);
}

}  // namespace driveid
