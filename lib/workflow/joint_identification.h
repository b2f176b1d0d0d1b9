// The identification of an elastic joint from its logs, as `drivetrain-fit
// joint` runs it (docs/models.md#elastic-joint, #joint-output-error): the
// inverse-dynamics fit that output error starts from, the method (`auto`
// from that fit and the logs), the fit, and the trace, plot and summary.
// The command parses, loads the logs, calls this, emits.
#pragma once

#include <string>
#include <vector>

#include "core/fit_result.h"
#include "fit/core/least_squares.h"
#include "logs/joint_log.h"
#include "models/joint.h"
#include "report/plot.h"

namespace driveid {

enum class JointMethod { kAuto, kInverseDynamics, kOutputError };

struct JointIdentificationOptions {
  JointMethod method = JointMethod::kAuto;
  std::vector<std::string> free;  ///< empty: the default for the logs
  double cutoff = 0.0;            ///< inverse dynamics: angle low-pass [Hz], 0: rate / 40
  double segment_seconds = 0.0;   ///< output error: JointOeOptions::segment_seconds
  FitOptions fit;                 ///< progress callback
  bool trace = false;             ///< build the trace CSV
  bool plot = false;              ///< build the plot panels
  /// Every bound on these fields (‹field› names the option); see core/option_check.h.
  bool IsValid(std::string* error) const;
};

struct JointIdentification {
  JointMethod method = JointMethod::kInverseDynamics;
  JointParameters params;
  FitResult fit;
  std::string model;                  ///< for the provenance
  std::string trace_csv;              ///< when asked for
  std::vector<PlotPanel> panels;      ///< when asked for
  std::vector<std::string> summary;   ///< lines for the text summary
};

/// Fits the joint to `logs` from `section`. `auto` takes output error when
/// every log has the motor torque, the link's Coulomb friction is neither
/// free nor given, and the inverse-dynamics fit (output error's start) shows
/// its filter near the resonance (cutoff < 4 x resonance; a link Coulomb
/// friction it finds is then warned of, not trusted) or, finding no link
/// Coulomb friction, leaves a term undetermined (relative std above 50 %,
/// not at its bound 0); the summary says why. Throws as FitJoint and FitJointOutputError;
/// OptionError for a cutoff with output error, a segment with inverse
/// dynamics.
JointIdentification IdentifyJoint(const std::vector<JointLog>& logs, const JointSection& section,
                                  const JointIdentificationOptions& options);

}  // namespace driveid
