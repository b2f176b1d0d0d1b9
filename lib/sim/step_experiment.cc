#include "sim/step_experiment.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "core/option_check.h"

#include "sim/drivetrain_simulator.h"
#include "sim/noise.h"

namespace driveid {
namespace {
}  // namespace

void ValidateStepExperiment(const StepExperiment& e) {
  RequireOption(std::isfinite(e.rate) && e.rate > 0.0, "‹rate›", e.rate, "rate > 0 Hz");
  RequireOption(std::isfinite(e.duration) && e.duration > 0.0, "‹duration›", e.duration, "duration > 0 s");
  RequireSampleCount(std::round(e.duration * e.rate) + 1, kMinStepLogSamples,
                     fmt::format("‹duration› {} at ‹rate› {}", e.duration, e.rate));
  RequireOption(std::isfinite(e.step_time) && e.step_time >= 0.0 && e.step_time < e.duration, "‹step_time›", e.step_time,
          "0 <= step time < duration");
  RequireOption(std::isfinite(e.step_torque), "‹step_torque›", e.step_torque, "finite");
  RequireOption(std::isfinite(e.noise) && e.noise >= 0.0, "‹noise›", e.noise, "noise >= 0");
  RequireOption(std::isfinite(e.offset), "‹offset›", e.offset, "finite");
}

StepLog SimulateStepExperiment(const DriveTrainParameters& params, const StepExperiment& e) {
  ValidateStepExperiment(e);
  StepLog log;
  log.path = "simulated";
  const long samples = std::lround(e.duration * e.rate) + 1;
  log.time.reserve(static_cast<std::size_t>(samples));
  log.motor_torque.reserve(static_cast<std::size_t>(samples));
  for (long k = 0; k < samples; ++k) {
    const double t = static_cast<double>(k) / e.rate;
    log.time.push_back(t);
    log.motor_torque.push_back(t >= e.step_time - 1e-9 / e.rate ? e.step_torque : 0.0);
  }
  DriveTrainSimulator simulator(e.model, params, {});
  DriveTrainResponse response;
  simulator.Simulate(params, log.time, log.motor_torque, false, &response);
  GaussianNoise noise(e.seed);
  log.link_torque = std::move(response.link_torque);
  for (double& y : log.link_torque) y += e.offset + (e.noise > 0.0 ? noise.Next(e.noise) : 0.0);
  return log;
}


}  // namespace driveid
