#include "workflow/cdrive_simulation.h"

#include <utility>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "logs/cdrive_log.h"
#include "models/missing_values.h"
#include "sim/cdrive_closed_loop.h"

namespace driveid {

bool CDriveSimulationRequest::IsValid(std::string* error) const {
  return OptionCheck(error)
      .Require(program == "translation" || program == "rotation" || program == "helical",
               "‹program› " + program + ": choose translation, rotation or helical")
      .Require(law.empty() || law == "PI" || law == "PD" || law == "PID", "‹law› " + law + ": choose PI, PD or PID")
      .Require(Positive(stroke), "‹stroke›", stroke, "stroke > 0 s")
      .Require(cycles >= 1 && cycles <= 1000, "‹cycles›", cycles, "1 <= cycles <= 1000")
      .Require(NotNegative(noise), "‹noise›", noise, "noise >= 0");
}

CDriveSimulation SimulateCDrive(const ParameterFile& file, const std::string& path,
                                const CDriveSimulationRequest& request, const std::string& command_line) {
  if (!file.Find<CDriveSection>()) throw InputError(fmt::format("{}: no 'cdrive' section", path));
  RequireModelValues(CDriveParameterTable(), *file.Find<CDriveSection>(), path, "cdrive", "the simulation");
  RequireValid(request);
  const CDriveParameters params =
      MakeModelParameters(CDriveParameterTable(), *file.Find<CDriveSection>(), CDriveParameters{}, "cdrive");
  CDriveControlSettings settings = MakeControlSettings(
      file.Find<CDriveControlSection>() ? *file.Find<CDriveControlSection>() : CDriveControlSection{});
  if (request.law == "PI") settings.law = ControlLaw::kPI;
  if (request.law == "PD") settings.law = ControlLaw::kPD;
  if (request.law == "PID") settings.law = ControlLaw::kPID;

  ClosedLoopOptions loop;
  loop.program = TableTwoProgram(request.program, request.stroke);
  loop.cycles = request.cycles;
  loop.torque_noise = request.noise;
  loop.seed = request.seed;
  const ClosedLoopResult result = SimulateClosedLoop(params, settings, loop);

  CDriveSimulation out;
  out.log_text = FormatCDriveLog(
      result.log,
      {"C-drive log (docs/formats.md#logs) made by: " + command_line,
       fmt::format("program {} (alpha_L {}, alpha_R {} rad), stroke {} s, {} cycles, {} at {} Hz, 13-bit encoders, "
                   "torque noise {} N m (seed {})",
                   loop.program.name, loop.program.amplitude_left, loop.program.amplitude_right, loop.program.stroke,
                   loop.cycles, ControlLawName(settings.law), 1.0 / settings.sample_time, request.noise, request.seed),
       fmt::format("truth: p {}, I_h {}, I_c {}, m {}, beta {}, gamma {}, delta {}, eta {}", params.lead,
                   params.hub_inertia, params.collar_inertia, params.collar_mass, params.viscous_motor,
                   params.viscous_collar, params.coulomb_motor, params.coulomb_collar)});
  if (request.plot) {
    std::vector<double> millimetres(result.tracking.translation_error);
    for (double& v : millimetres) v *= 1e3;
    out.panels = {{fmt::format("tracking error in u, {} ({})", loop.program.name, ControlLawName(settings.law)),
                   "u error [mm]",
                   {{"u_ref - u", result.tracking.time, millimetres, false}}},
                  {"tracking error in theta", "theta error [rad]",
                   {{"theta_ref - theta", result.tracking.time, result.tracking.rotation_error, false}}}};
  }
  if (request.trace) {
    out.trace_csv =
        "# tracking errors from the encoder angles (docs/models.md#c-drive coordinates)\nt,u_error,theta_error\n";
    for (std::size_t k = 0; k < result.tracking.time.size(); ++k) {
      out.trace_csv += fmt::format("{},{:.6g},{:.6g}\n", result.tracking.time[k], result.tracking.translation_error[k],
                                   result.tracking.rotation_error[k]);
    }
  }
  out.summary_json = {{"program", loop.program.name},
                      {"law", ControlLawName(settings.law)},
                      {"endpoint_u_error", result.endpoint_translation_error},
                      {"endpoint_theta_error", result.endpoint_rotation_error},
                      {"max_u_error", result.max_translation_error},
                      {"max_theta_error", result.max_rotation_error},
                      {"switches", result.switches}};
  out.summary = fmt::format(
      "{}, {}: end-point error u {:.4f} mm, theta {:.5f} rad (seed 001: < 0.1 mm, < 0.01 rad); max over the "
      "run u {:.3f} mm, theta {:.4f} rad; {} stick/slip switches\n",
      loop.program.name, ControlLawName(settings.law), result.endpoint_translation_error * 1e3,
      result.endpoint_rotation_error, result.max_translation_error * 1e3, result.max_rotation_error, result.switches);
  return out;
}

}  // namespace driveid
