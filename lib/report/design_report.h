// Text, JSON, reference CSV and plot of an excitation design
// (design/axis_excitation.h, docs/models.md#excitation-design).
#pragma once

#include <string>
#include <vector>

#include "design/axis_excitation.h"
#include "logs/axis_reference.h"
#include "report/json.h"
#include "report/plot.h"

namespace driveid {

/// The design beside the four equal sines: per free parameter the prior,
/// both predicted stds and their ratio; the limits met; the lines.
std::string FormatAxisDesign(const AxisDesign& design, bool linear);

/// `predicted_std.NAME`, `naive.predicted_std.NAME`, the limits' peaks, lines.
Json AxisDesignJson(const AxisDesign& design);

/// The designed reference on the logging grid over `duration`.
AxisReference DesignedReference(const AxisDesign& design, const AxisParameters& prior, double rate,
                                double duration);

/// The reference (position, the prior's torque) of both over one period,
/// and each line's acceleration amplitude against frequency.
std::vector<PlotPanel> AxisDesignPanels(const AxisDesign& design, const AxisParameters& prior, double rate);

}  // namespace driveid
