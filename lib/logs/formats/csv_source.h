// CSV text (docs/formats.md#logs): with or without a header row; comma,
// semicolon, tab or blank separated; '#' comment lines; a UTF-8 byte-order
// mark skipped. The last format tried: it takes any file the others do not.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "logs/table_source.h"

namespace driveid {

/// The CSV reader alone.
std::unique_ptr<TableSource> OpenCsvSource(const std::string& path, const std::string& text, const CsvFormat& format);

}  // namespace driveid
