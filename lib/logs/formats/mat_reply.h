// What the MAT reader process (lib/logs/formats/mat_reader.h) sends the tools over a
// pipe: '\0', the variable count, per variable its dotted name, rows, cols
// and values (column-major doubles), then the count of notes and the notes
// (skipped variables and why); or '\1' and the message of an InputError.
// Counts and sizes are 8-byte integers in the machine's order (both ends
// are the same build).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace driveid {

/// Elements one MAT file may expand to (2 GiB of doubles): a compressed
/// variable can claim far more than its bytes.
constexpr std::size_t kMaxMatElements = std::size_t{1} << 28;

struct MatVariable {
  std::string name;  ///< dotted path of a struct field, e.g. "rec.pos"
  std::size_t rows = 0, cols = 0;
  std::vector<double> data;  ///< column-major
};

struct MatContents {
  std::vector<MatVariable> variables;
  std::vector<std::string> notes;
};

std::string SerialiseMatReply(const MatContents& contents);
std::string SerialiseMatError(const std::string& message);

/// The contents of a reply; throws InputError with the reader's message, or
/// naming `path` for a reply cut short or too large.
MatContents DeserialiseMatReply(const std::string& path, const std::string& reply);

}  // namespace driveid
