// JSON output of the tools: one document per run, built with nlohmann-json
// (ordered keys, so output is deterministic and in the order written).
// Non-finite numbers become null; bytes that are not UTF-8 (e.g. in a file
// name) are replaced rather than aborting the run.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace driveid {

using Json = nlohmann::ordered_json;

/// Compact text of a document, newline-terminated.
inline std::string DumpJson(const Json& document) {
  return document.dump(-1, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace driveid
