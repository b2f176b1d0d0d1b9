// WPILib SysId JSON (docs/formats.md#logs): each test (and side) of
// the file as a table source (logs/formats/sysid_source.cc).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "logs/table_source.h"

namespace driveid {

/// The SysId JSON reader alone.
std::vector<std::unique_ptr<TableSource>> OpenSysIdSources(const std::string& path, const std::string& text,
                                                           const LogSelection& format);

}  // namespace driveid
