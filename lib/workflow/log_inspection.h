// What the tools read from a log file (`drivetrain-fit inspect`): its
// sources (a SysId file has one per test), columns with position and range,
// sample count, rate and jitter, time span, and the expressions and crops
// applied (docs/formats.md#logs).
#pragma once

#include <string>
#include <vector>

#include "logs/log_input.h"
#include "logs/table_source.h"
#include "report/json.h"

namespace driveid {

struct InspectedColumn {
  std::string name;       ///< as addressed (header name, MAT path, "#k"); logical name for mapped ones
  std::string source;     ///< for a mapped column: its expression
  std::size_t position = 0;  ///< 1-based (0 for mapped columns)
  std::size_t length = 0;
  double min = 0.0, max = 0.0;
  std::string problem;    ///< why it cannot be a log column ("" if it can)
};

struct InspectedLog {
  std::string path, segment, format;
  std::size_t rows = 0;
  std::vector<SourceVariable> variables;  ///< a MAT file's variables and struct fields
  std::vector<InspectedColumn> columns;  ///< every column of the source (of a MAT file: on request)
  std::vector<InspectedColumn> mapped;   ///< t and each --col, after expressions and crops
  bool has_time = false;
  double start = 0.0, end = 0.0;         ///< time span [s]
  double rate = 0.0;                     ///< 1 / median step [Hz]
  double jitter = 0.0;                   ///< (max step - min step) / median step
  std::vector<std::string> notes;        ///< reader notes, expressions, crops
  std::string time_problem;              ///< why there is no time base
};

/// Inspects one source with the options a fit would use. A source with
/// variables (MAT) lists them, and its columns only with `list_columns`
/// (a file of structs has tens of thousands); other sources list columns.
InspectedLog InspectLog(const TableSource& source, const LogInputOptions& options, bool list_columns = false);

std::string FormatLogInspection(const InspectedLog& log);
Json LogInspectionJson(const InspectedLog& log);

}  // namespace driveid
