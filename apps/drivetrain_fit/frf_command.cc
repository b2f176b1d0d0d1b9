// drivetrain-fit frf: frequency response, resonance and anti-resonance, and
// the two-mass joint fitted to it (docs/models.md#frequency-response).
#include <cmath>
#include <cstdio>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "common/cli_support.h"
#include "common/command_registry.h"
#include "common/log_input_options.h"
#include "core/errors.h"
#include "params/parameter_file.h"
#include "workflow/frequency_response_run.h"

namespace driveid::cli {
namespace {

struct FrfCliOptions {
  std::vector<std::string> logs;
  std::string params;
  std::string input, output, reference, link;
  std::string output_is, link_is = "position";
  double resolution = 0.0, period = 0.0;
  std::string method = "auto";
  std::vector<double> band;
  std::string fit = "none";
  std::string hold = "zoh";
  std::vector<std::string> free = TwoMassFitOptions{}.free;
  std::string measured, frequency_unit = "hz", magnitude_unit = "abs", phase_unit = "deg";
  bool transpose = false;
  LogInputCli log_input;
  FitOutputOptions out;
};

CLI::App* Setup(CLI::App& app, FrfCliOptions& o) {
  CLI::App* c = app.add_subcommand(
      "frf", "Frequency response (Welch H1, closed loop S_ry/S_ru, or per period), resonance and anti-resonance, "
             "and the two-mass joint fitted to it (docs/models.md#frequency-response)");
  c->add_option("logs", o.logs, "logs (CSV, MAT, SysId JSON; docs/formats.md#logs) of one rate");
  c->add_option("--measured", o.measured,
                "a frequency response measured elsewhere: columns frequency, magnitude, phase (optional coherence; "
                "map others with --col), fitted instead of logs");
  c->add_option("--frequency-unit", o.frequency_unit, "of --measured")->capture_default_str()
      ->check(CLI::IsMember({"hz", "rad/s"}));
  c->add_option("--magnitude-unit", o.magnitude_unit, "of --measured")->capture_default_str()
      ->check(CLI::IsMember({"abs", "db"}));
  c->add_option("--phase-unit", o.phase_unit, "of --measured")->capture_default_str()
      ->check(CLI::IsMember({"deg", "rad"}));
  c->add_flag("--transpose", o.transpose,
              "--measured stores one signal per row (frequency, magnitude, phase as rows; a row may start with its "
              "name; docs/formats.md#logs)");
  c->add_option("--input", o.input, "the torque: a column expression as --col takes (default tau, or i with joint.k_t)");
  c->add_option("--output", o.output, "the motor-side output (default qd_motor if logged, else q_motor)");
  c->add_option("--output-is", o.output_is, "what --output is (default from its name: q_* position, qd_* rate)")
      ->check(CLI::IsMember({"position", "rate", "acceleration"}));
  c->add_option("--reference", o.reference,
                "the injected excitation or set-point: closed-loop estimate S_ry/S_ru (not biased by the feedback)");
  c->add_option("--link", o.link, "a link-side signal (link angle): its response is fitted jointly");
  c->add_option("--link-is", o.link_is, "what --link is")->capture_default_str()
      ->check(CLI::IsMember({"position", "rate", "acceleration"}));
  c->add_option("--resolution", o.resolution, "Welch bin width [Hz] (default: about 8 averages)")
      ->check(FiniteAbove(0.0));
  c->add_option("--method", o.method, "auto (periodic when the excitation repeats), welch or periodic")
      ->capture_default_str()->check(CLI::IsMember({"auto", "welch", "periodic"}));
  c->add_option("--period", o.period, "period of a periodic excitation [s] (default: detected)")->check(FiniteAbove(0.0));
  c->add_option("--band", o.band, "LO,HI: band of the fit and of the features [Hz] (default: the coherent bins)")
      ->delimiter(',')->expected(2)->check(FiniteAtLeast(0.0));
  c->add_option("--fit", o.fit, "none, or two-mass: fit the joint (docs/models.md#elastic-joint)")
      ->capture_default_str()->check(CLI::IsMember({"none", "two-mass"}));
  c->add_option("--hold", o.hold, "zoh: the torque is held between samples (the model is sampled exactly); none: "
                                  "continuous")
      ->capture_default_str()->check(CLI::IsMember({"zoh", "none"}));
  c->add_option("--params", o.params, "parameter file with a joint section (gear_ratio, fixed values; optional)");
  AddFreeOption(*c, o.free,
                "parameters of --fit two-mass: motor_inertia, link_inertia, stiffness, damping, motor_viscous, "
                "link_viscous, delay [s] (default motor_inertia,link_inertia,stiffness,damping,motor_viscous)");
  AddLogInputOptions(*c, o.log_input, "tau=#4");
  c->add_option("-o,--output-file", o.out.output, "write the parameter file (joint and frf sections) here");
  c->add_option("--csv,--trace", o.out.trace,
                "write the response as CSV (docs/formats.md#frequency-response-csv); --trace as in the other commands");
  c->add_option("--plot", o.out.plot, "render the Bode plot (.png or .svg)")->check(PlotPath());
  c->add_flag("--json", o.out.json, "print the summary as one JSON object instead of text");
  c->add_flag("-q,--quiet", o.out.quiet, "print no summary");
  c->add_flag("-v,--verbose", o.out.verbose, "log solver iterations on stderr");
  c->add_flag("--strict", o.out.strict,
              "warnings (no resonance in the band, adequacy; docs/models.md#reading-the-resonance) fail the run: exit "
              "4, nothing written");
  c->add_option("--max-log-size", o.out.max_log_gib, "largest log to read [GiB]")->capture_default_str()
      ->check(FiniteWithin(1e-6, 1024.0));
  c->footer("Examples:\n"
            "  drivetrain-fit frf bench.csv --reference r --fit two-mass --params joint.yaml -o joint_fit.yaml "
            "--plot bode.png\n"
            "  drivetrain-fit frf swept1.txt --no-header --delimiter tab --col t=#1 --input '#3' --output '#5' "
            "--output-is position --fit two-mass\n"
            "  drivetrain-fit frf --measured bode.csv --magnitude-unit db --output-is rate --fit two-mass");
  return c;
}

FrfResult AnalyseLogs(FrfCliOptions& o, const JointSection& section, FrfOptions& options, FitProvenance& provenance);
void Emit(const FrfCliOptions& o, const ParameterFile& start, const JointSection& section, const FrfResult& result,
          const FitProvenance& provenance);

// Reads --measured: frequency [Hz], magnitude (linear) and phase [rad].
MeasuredResponse ReadMeasured(const FrfCliOptions& o, FitProvenance& provenance) {
  MeasuredResponse m;
  LoadLogs<int>(
      {o.measured}, o.log_input, o.out, provenance, {"frequency", "magnitude", "phase", "?coherence"},
      [&](CsvLog csv) {
        if (!m.frequency.empty()) throw InputError(fmt::format("{}: --measured takes one response", o.measured));
        m.frequency = csv.columns[0];
        m.magnitude = csv.columns[1];
        m.phase = csv.columns[2];
        m.coherence = csv.columns[3];
        return 0;
      },
      "frequency", o.transpose);
  return MeasuredResponseInSi(std::move(m), {o.frequency_unit == "rad/s", o.magnitude_unit == "db", o.phase_unit == "deg"});
}

void Run(FrfCliOptions o, const std::string& command_line) {
  if (o.logs.empty() == o.measured.empty()) {
    throw OptionError("frf: give logs, or --measured FILE (not both)");
  }
  CheckFitOutputs(o.out, LogCommandInputs(o.measured.empty() ? o.logs : std::vector<std::string>{o.measured},
                                          o.params, o.log_input, {}));
  ParameterFile start;
  JointSection section;
  if (!o.params.empty()) {
    start = ReadParameterFile(o.params);
    if (const auto* joint = start.Find<JointSection>()) section = *joint;
  }
  if (o.transpose && o.measured.empty()) throw OptionError("--transpose applies to --measured");
  if (!o.measured.empty() && (!o.input.empty() || !o.reference.empty() || !o.link.empty())) {
    throw OptionError("--measured: --input, --reference and --link are for logs");
  }
  FitProvenance provenance;
  provenance.command = command_line;
  provenance.version = DRIVEID_VERSION;
  provenance.model = "frequency response (docs/models.md#frequency-response)";
  FrfOptions options = MakeFrfOptions(
      {o.resolution, o.period, o.method, o.fit == "two-mass", o.hold == "zoh", o.free, o.link_is, o.band});
  SetProgress(options.two_mass.fit, o.out.verbose);
  FrfResult result;
  if (!o.measured.empty()) {
    if (o.output_is.empty()) throw OptionError("--measured: say what its output is with --output-is position|rate|acceleration");
    options.two_mass.motor_output = ResponseQuantityFromName(o.output_is, "--output-is");
    result = AnalyseMeasuredResponse(ReadMeasured(o, provenance), section, options);
  } else {
    result = AnalyseLogs(o, section, options, provenance);
  }
  Emit(o, start, section, result, provenance);
}

FrfResult AnalyseLogs(FrfCliOptions& o, const JointSection& section, FrfOptions& options, FitProvenance& provenance) {
  // Logical columns: t, the input, the output, optional reference and link.
  std::vector<std::string> required = {"t", o.input.empty() ? "tau|i" : "tau",
                                       o.output.empty() ? "qd_motor|q_motor" : "y"};
  if (!o.input.empty()) o.log_input.columns.push_back("tau=" + o.input);
  if (!o.output.empty()) {
    o.log_input.columns.push_back("y=" + o.output);
    if (o.output_is.empty()) o.output_is = ResponseQuantityOfSignal(o.output);
    if (o.output_is.empty()) {
      throw OptionError(fmt::format("--output {}: say what it is with --output-is position|rate|acceleration", o.output));
    }
  }
  if (!o.reference.empty()) {
    required.push_back("reference");
    o.log_input.columns.push_back("reference=" + o.reference);
  }
  if (!o.link.empty()) {
    required.push_back("q_link");
    o.log_input.columns.push_back("q_link=" + o.link);
  }
  const double k_t = section.torque_constant.value_or(0.0);
  std::vector<FrfSignals> signals;
  std::string output_name;
  LoadLogs<int>(o.logs, o.log_input, o.out, provenance, required, [&](CsvLog csv) {
    output_name = csv.names[2];
    signals.push_back(FrfSignalsFromLog(std::move(csv), k_t, !o.reference.empty(), !o.link.empty()));
    return 0;
  });
  if (o.output.empty()) o.output_is = output_name == "qd_motor" ? "rate" : "position";
  options.two_mass.motor_output = ResponseQuantityFromName(o.output_is, "--output-is");
  return AnalyseFrequencyResponse(signals, section, options);
}

void Emit(const FrfCliOptions& o, const ParameterFile& start, const JointSection& section, const FrfResult& result,
          const FitProvenance& provenance) {
  FrfOutputs assembled =
      AssembleFrfOutputs(start, section, result, provenance, !o.out.trace.empty(), !o.out.plot.empty(), o.out.json);
  FitOutputs outputs;
  outputs.provenance = provenance;
  outputs.parameter_file = std::move(assembled.parameter_file);
  outputs.trace_csv = std::move(assembled.trace_csv);
  outputs.plot_panels = std::move(assembled.panels);
  outputs.plot_x_label = "frequency [Hz]";
  outputs.plot_log_x = true;
  outputs.fit = std::move(assembled.fit);
  // The summary goes where the fit table would (stdout with -o, else
  // stderr), inside the transaction: a failed stdout changes no file.
  outputs.summary = std::move(assembled.summary);
  EmitFitOutputs(o.out, outputs);
}

const bool kRegistered = RegisterCommand(Command<FrfCliOptions>(
    "drivetrain-fit", "", 27, [](CLI::App& parent, FrfCliOptions& o) { return Setup(parent, o); },
    [](const FrfCliOptions& o, const std::string& line) { Run(o, line); }));

}  // namespace
}  // namespace driveid::cli
