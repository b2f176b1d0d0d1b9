#include "sim/cdrive_closed_loop.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "core/option_check.h"

#include "control/cdrive_controller.h"
#include "sim/cdrive_plant.h"
#include "sim/noise.h"

namespace driveid {

bool ClosedLoopOptions::IsValid(std::string* error) const {
  return OptionCheck(error)
      .Require(Positive(program.stroke), "‹stroke›", program.stroke, "stroke > 0 s")
      .Require(cycles >= 1 && cycles <= 1000, "‹cycles›", cycles, "1 <= cycles <= 1000")
      .Require(NotNegative(torque_noise), "‹noise›", torque_noise, "noise >= 0");
}

void ValidateClosedLoop(const ClosedLoopOptions& o, const CDriveControlSettings& s) {
  RequireValid(o);
  RequireSampleCount(std::round(2.0 * o.program.stroke * o.cycles / s.sample_time) + 1, kMinCDriveLogSamples,
                     fmt::format("‹stroke› {} with ‹cycles› {} at cdrive.control.sample_time {} s", o.program.stroke,
                                 o.cycles, s.sample_time));
  RequireValid(s);
}

ClosedLoopResult SimulateClosedLoop(const CDriveParameters& params, const CDriveControlSettings& settings,
                                    const ClosedLoopOptions& options) {
  ValidateClosedLoop(options, settings);
  CDrivePlant plant(params);
  plant.Reset({});
  CDriveController controller(params, settings);
  controller.Reset();
  GaussianNoise noise(options.seed);
  ClosedLoopResult result;
  const double stroke = options.program.stroke;
  const long periods = std::lround(2.0 * stroke * options.cycles / settings.sample_time);
  const long periods_per_stroke = std::lround(stroke / settings.sample_time);
  result.log.path = "simulated";
  // One controller period per step, as the drive's real-time loop runs it:
  // read the quantised encoders, compute the torque, hold it over the period
  // (zero-order hold) while the plant integrates. The logged torque carries
  // the measurement noise; the plant gets the commanded one (the noise is
  // the logger's, not a disturbance).
  for (long k = 0; k <= periods; ++k) {
    const double t = static_cast<double>(k) * settings.sample_time;
    const auto left = CalcProgramReference(options.program.amplitude_left, stroke, t);
    const auto right = CalcProgramReference(options.program.amplitude_right, stroke, t);
    const CDrivePlantState& state = plant.state();
    const Vector2 encoder = {QuantizeEncoder(state.angle[0], settings.encoder_counts),
                             QuantizeEncoder(state.angle[1], settings.encoder_counts)};
    const Vector2 torque = controller.Update({left.angle, right.angle}, {left.rate, right.rate}, encoder);

    result.log.time.push_back(t);
    result.log.angle_left.push_back(encoder[0]);
    result.log.angle_right.push_back(encoder[1]);
    result.log.torque_left.push_back(torque[0] + (options.torque_noise > 0.0 ? noise.Next(options.torque_noise) : 0.0));
    result.log.torque_right.push_back(torque[1] + (options.torque_noise > 0.0 ? noise.Next(options.torque_noise) : 0.0));

    // Tracking errors in the collar's coordinates (what the process sees),
    // from the encoder angles the controller had: the worst over the run
    // and at the stroke ends, where the program stops and settles.
    const double error_left = left.angle - encoder[0], error_right = right.angle - encoder[1];
    const double u_error = CalcCollarTranslation(params.lead, error_left, error_right);
    const double theta_error = CalcCollarRotation(error_left, error_right);
    result.tracking.time.push_back(t);
    result.tracking.translation_error.push_back(u_error);
    result.tracking.rotation_error.push_back(theta_error);
    result.max_translation_error = std::max(result.max_translation_error, std::abs(u_error));
    result.max_rotation_error = std::max(result.max_rotation_error, std::abs(theta_error));
    if (k > 0 && k % periods_per_stroke == 0) {
      result.endpoint_translation_error = std::max(result.endpoint_translation_error, std::abs(u_error));
      result.endpoint_rotation_error = std::max(result.endpoint_rotation_error, std::abs(theta_error));
    }
    if (k < periods) plant.Advance(t, t + settings.sample_time, torque);
  }
  result.switches = plant.switch_count();
  return result;
}

}  // namespace driveid
