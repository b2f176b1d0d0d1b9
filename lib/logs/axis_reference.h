// A position reference for an axis (docs/formats.md#references): the CSV
// `design axis` writes and `simulate axis --reference` follows, columns
// t [s], q [rad or m] and, optionally, qd [/s] and qdd [/s^2]. A reference
// without qd or qdd has them by central differences of q on its times.
#pragma once

#include <string>
#include <vector>

namespace driveid {

struct AxisReference {
  std::string path;
  std::vector<double> time, position, rate, acceleration;
};

/// Reads a reference; throws InputError naming the file and line.
AxisReference ReadAxisReference(const std::string& path);

/// The CSV text of a reference (t, q, qd, qdd), '#' comment lines first.
std::string FormatAxisReference(const AxisReference& reference, const std::vector<std::string>& comments);

}  // namespace driveid
