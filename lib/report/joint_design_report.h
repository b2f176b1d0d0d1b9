// Text, JSON, excitation CSV and plot of a joint excitation design
// (design/joint_excitation.h, docs/models.md#joint-excitation-design).
#pragma once

#include <string>
#include <vector>

#include "design/joint_excitation.h"
#include "logs/torque_reference.h"
#include "report/json.h"
#include "report/plot.h"

namespace driveid {

/// The design beside the default multisine at the same rms: per free
/// parameter the prior, both predicted stds and their ratio; the peaks; the
/// strongest lines.
std::string FormatJointDesign(const JointDesign& design);

/// `predicted_std.NAME`, `naive.predicted_std.NAME`, rms, peaks, lines.
Json JointDesignJson(const JointDesign& design);

/// The designed excitation on the logging grid over `duration`.
TorqueReference DesignedExcitation(const JointDesign& design, double rate, double duration);

/// Both excitations over one period and their line amplitudes against
/// frequency, with the prior's motor-rate response.
std::vector<PlotPanel> JointDesignPanels(const JointDesign& design, double rate);

}  // namespace driveid
