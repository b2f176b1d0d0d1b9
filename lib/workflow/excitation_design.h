// The `design` runs (docs/models.md#excitation-design): the prior from a
// parameter file, the design, the reference (axis) or torque excitation
// (joint) CSV with its comments, the plot panels, and the text or JSON the
// command prints — everything but writing the files and the terminal.
#pragma once

#include <string>
#include <vector>

#include "design/axis_excitation.h"
#include "design/joint_excitation.h"
#include "params/parameter_file.h"
#include "report/plot.h"

namespace driveid {

/// What the command asks for besides the design's own options.
struct ExcitationDesignRequest {
  std::string params_path;            ///< the prior's file, for messages
  std::vector<double> band;           ///< {LO, HI} [Hz] or empty (the design's default)
  std::vector<std::string> targets;   ///< the parameters that count (empty: all free)
  bool csv = false;                   ///< build the reference CSV
  bool plot = false;                  ///< build the plot panels
  bool json = false;                  ///< print JSON instead of the text
  std::string command_line;           ///< for the CSV's provenance comment
  /// A band is two frequencies or none.
  bool IsValid(std::string* error) const;
};

struct ExcitationDesignRun {
  std::string csv;                  ///< the reference (axis: t,q,qd,qdd) or excitation (joint: t,tau)
  std::vector<PlotPanel> panels;    ///< over one period (axis: with the prior's torque and the lines)
  std::string printed;              ///< the text, or the JSON document
};

/// design axis: InputError without an axis section or with a value it
/// needs missing; OptionError (‹noise›) when neither ‹noise› nor the prior's
/// inverse-dynamics residuals give the torque noise.
ExcitationDesignRun DesignAxisRun(const ParameterFile& file, AxisDesignOptions design, const ExcitationDesignRequest& r);

/// design joint: InputError without a joint section or its gear ratio.
ExcitationDesignRun DesignJointRun(const ParameterFile& file, JointDesignOptions design, const ExcitationDesignRequest& r);

}  // namespace driveid
