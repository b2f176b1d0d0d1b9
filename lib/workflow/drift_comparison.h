// Parameter files compared with a base (docs/guide.md#fleets-and-drift):
// for each estimate of the base's fit (fit.estimates, value and std) that a
// file also holds, the relative change (v - v0) / |v0| and
// z = (v - v0) / sqrt(s^2 + s0^2); the drift gate flags the parameters
// whose change exceeds a percentage and/or a z (both, when both are given),
// and names what it cannot judge. The comparison's rendering is
// report/parameter_comparison.h.
#pragma once

#include <string>
#include <vector>

#include "core/fit_result.h"
#include "report/parameter_comparison.h"

namespace driveid {

/// Compares `other` with `base` (estimates by name). Parameters asked for
/// in `gate.parameters` that the base lacks are refused (InputError naming
/// them).
FileComparison CompareEstimates(const std::string& file, const std::vector<ParameterEstimate>& base,
                                const std::vector<ParameterEstimate>& other, const DriftGate& gate);

}  // namespace driveid
