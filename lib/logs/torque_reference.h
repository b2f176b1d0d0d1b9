// An injected torque excitation for the elastic joint
// (docs/formats.md#references): the CSV `design joint` writes and
// `simulate joint --reference` injects, columns t [s] and tau [N m, log
// units], sampled at the logging rate.
#pragma once

#include <string>
#include <vector>

namespace driveid {

struct TorqueReference {
  std::string path;
  std::vector<double> time, torque;
};

/// Reads an excitation; throws InputError naming the file and line (or the
/// file, for fewer than 16 rows or time steps that are not constant).
TorqueReference ReadTorqueReference(const std::string& path);

/// Its constant rate [Hz] (checked by ReadTorqueReference).
double TorqueReferenceRate(const TorqueReference& reference);

/// The CSV text (t, tau), '#' comment lines first.
std::string FormatTorqueReference(const TorqueReference& reference, const std::vector<std::string>& comments);

}  // namespace driveid
