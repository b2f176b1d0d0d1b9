// A table stored one signal per row (a Bode export whose rows are
// frequency, magnitude, phase), turned into the one-signal-per-column text
// the log reader takes (docs/formats.md#logs).
#pragma once

#include <string>

namespace driveid {

/// '#' lines are kept first, blank lines dropped; the other lines are split
/// on the first of ',', ';', tab found in the first of them (else on runs of
/// spaces), and must all have the same number of cells (InputError naming
/// `path`, the line and both counts). Returns comma-separated text whose
/// line j holds cell j of every row; a row that starts with a name gives a
/// header (the names). Cells are copied as they are (no quoting).
std::string TransposeTable(const std::string& path, const std::string& text);

}  // namespace driveid
