// Synthetic axis logs (docs/models.md#axis) in the axis-log format: the axis follows a
// prescribed motion exactly; the force is its inverse dynamics plus Gaussian
// noise; positions are quantised like an encoder.
//   multisine: q = A (0.6 sin(2 pi 0.3 t) + 0.3 sin(2 pi 1.1 t + 1) + 0.1 sin(2 pi 2.3 t + 2))
//   constant:  q = speed t (constant rate: friction only)
//   reference: q, q', q'' of a reference file (logs/axis_reference.h) at its
//              own times (`design axis` writes one); rate and duration unused
#pragma once

#include <cstdint>
#include <string>

#include "logs/axis_log.h"
#include "logs/axis_reference.h"
#include "models/axis.h"

namespace driveid {

struct AxisExperiment {
  std::string profile = "multisine";
  double rate = 1000.0;        ///< [Hz]
  double duration = 10.0;      ///< [s]
  double amplitude = 1.0;      ///< A [rad or m]
  double speed = 1.0;          ///< constant profile [rad/s or m/s]
  double resolution = 2.0 * 3.14159265358979323846 / 8192.0;  ///< position quantum (0 = none)
  double noise = 0.0;          ///< std of force noise
  std::uint64_t seed = 1;
  AxisReference reference{};   ///< the "reference" profile's samples
};

/// Throws OptionError naming a bad option.
AxisLog SimulateAxisExperiment(const AxisParameters& params, const AxisExperiment& experiment);

}  // namespace driveid
