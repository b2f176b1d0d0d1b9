// `report` for an elastic joint's and a frequency response's sections
// (docs/models.md#elastic-joint, #frequency-response): the parameters and
// what follows from them — resonance f_r = sqrt(k (1/J_m + 1/J_l)) / 2 pi,
// anti-resonance f_a = sqrt(k / J_l) / 2 pi, the relative mode's damping
// ratio zeta = d w_r / (2 k), inertia ratio J_l / J_m, total inertia — and
// the measured resonances with their std.
#pragma once

#include <string>

#include "params/parameter_file.h"
#include "report/json.h"

namespace driveid {

/// Text and JSON of the joint and frf sections present ("" and an empty
/// object when neither: the JSON is merged into the report's).
std::string FormatJointReport(const ParameterFile& file);
Json JointReportJson(const ParameterFile& file);

}  // namespace driveid
