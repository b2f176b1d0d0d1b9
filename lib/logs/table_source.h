// Where a log's columns come from (docs/formats.md#logs): a CSV file (with or
// without a header row; comma, semicolon, tab or blank separated), a MATLAB
// MAT file (v5, v7.3), one test of a WPILib SysId JSON file or of a
// SysIdRoutine in a WPILib DataLog (.wpilog). A source has
// columns addressed by name, by 1-based position `#k`, or (MAT) by variable
// path, and may have named scalars for column expressions.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "logs/log_selection.h"

namespace driveid {

/// A source's note that the user must see (printed by the tools on
/// stderr, kept in the fit's provenance): it starts with this.
inline constexpr const char* kReaderWarning = "warning:";


/// Columns read from a source: values per requested column, and the file
/// line of each row where the source is text (empty otherwise).
struct TableData {
  std::vector<std::vector<double>> columns;
  std::vector<int> line_numbers;
};

/// A variable of a structured source (a MAT file): its path, size and how
/// its data is addressed (`inspect` lists these rather than every column).
struct SourceVariable {
  std::string name;  ///< dotted path, e.g. "rec.act_pos_mot_deg"
  std::size_t rows = 0, cols = 0;
  std::string address;  ///< e.g. "rows rec.x(1,:) .. rec.x(6,:); columns rec.x(:,k)"
};

class TableSource {
 public:
  virtual ~TableSource() = default;
  /// The file, and the part of it ("slow-forward", "left") this source is.
  virtual std::string path() const = 0;
  virtual std::string segment() const { return {}; }
  /// "csv", "mat" or "sysid".
  virtual std::string format() const = 0;
  /// The position unit the file declares (SysId `units`), "" if none.
  virtual std::string units() const { return {}; }
  /// The mechanism the file declares (SysId `test`: Simple, Elevator, Arm, Drivetrain), "" if none.
  virtual std::string mechanism() const { return {}; }
  /// The line of a CSV header row (0: none).
  virtual int header_line() const { return 0; }
  /// Addressable columns in position order (`#k` is the k-th); "" for a
  /// column without a name (a CSV without header).
  virtual std::vector<std::string> column_names() const = 0;
  /// Rows of each column (0 when they differ, as in a MAT file of several
  /// variables; then only columns of equal length can make a log).
  virtual std::vector<std::size_t> column_lengths() const = 0;
  /// The variables of a structured source (empty for CSV and SysId).
  virtual std::vector<SourceVariable> variables() const { return {}; }
  /// A named constant (MAT scalar variables), for column expressions.
  virtual std::optional<double> scalar(const std::string& name) const {
    (void)name;
    return std::nullopt;
  }
  /// Reads the columns with the given indices; throws InputError naming the
  /// file (and line, or variable) of a value that is not a finite number.
  virtual TableData Read(const std::vector<std::size_t>& columns) const = 0;
  /// Things a reader skipped or assumed (no header row, a delimiter, a
  /// variable it cannot read): shown by `inspect`, kept in the provenance.
  virtual std::vector<std::string> notes() const { return {}; }
  /// Comment lines of a text log, without the leading '#'.
  virtual std::vector<std::string> comments() const { return {}; }
  /// Default references for logical columns ("q" -> "position"), e.g. from
  /// a SysId file's layout; "" when the name is used as it is.
  virtual std::string DefaultReference(const std::string& logical) const {
    (void)logical;
    return {};
  }

  /// The index of a reference: `#k` (1-based), or a name that occurs once.
  /// Returns nullopt when absent; throws InputError for an ambiguous name.
  /// (The MAT reader also resolves rows of matrices, `name(k,:)`.)
  virtual std::optional<std::size_t> Find(const std::string& reference) const;
};

/// A source whose columns are already in memory — a SysId JSON test, a
/// WPILog routine's test, a bag topic's table — or, without columns, a
/// catalog of a structured file's entries (`variables`) for `inspect`.
struct MemorySourceParts {
  std::string path, segment, format, units, mechanism;
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;  ///< one per name, of equal length
  std::vector<std::string> notes;
  std::map<std::string, std::string> defaults;  ///< logical name -> column (DefaultReference)
  std::vector<SourceVariable> variables;
};
std::unique_ptr<TableSource> MakeMemorySource(MemorySourceParts parts);

/// The columns a SysId test's q, qd and tau read by default: position,
/// velocity (the logged rate, as SysId uses it) and voltage.
std::map<std::string, std::string> SysIdDefaults();

/// One of the names a file offers (`found`: motors, topics, joints): the
/// one `wanted` (OptionError listing them when absent: "‹option› NAME: PATH
/// has no such WHAT (found: ...)"), else the only one; several and none
/// wanted: OptionError asking for ‹option›; none at all: InputError.
std::string ChooseName(const std::vector<std::string>& found, const std::string& wanted, const char* what,
                       const char* option, const std::string& path);

/// How to read text sources.
struct CsvFormat {
  char delimiter = 0;      ///< 0: detect (',', ';', tab, else blanks)
  bool no_header = false;  ///< the first row is data (also detected: a first row of numbers)
  std::size_t skip_rows = 0;  ///< lines skipped before the header (a drive export's preamble), kept as comments
  std::size_t max_line_bytes = 1 << 20;
};

}  // namespace driveid
