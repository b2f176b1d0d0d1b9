// The WPILog format (docs/formats.md#wpilog): a SysIdRoutine's tests as
// table sources (logs/formats/wpilog_source.cc), the log itself parsed by
// logs/formats/wpilog.h.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "logs/table_source.h"

namespace driveid {

/// The WPILog reader alone: a SysIdRoutine's tests, or with
/// LogSelection::catalog one source listing the log's entries.
std::vector<std::unique_ptr<TableSource>> OpenWpilogSources(const std::string& path, const std::string& text,
                                                            const LogSelection& format);

}  // namespace driveid
