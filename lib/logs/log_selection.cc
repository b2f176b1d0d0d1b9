#include "logs/log_selection.h"

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {

void SetWpilogEntry(WpilogEntries& entries, const std::string& given) {
  const auto eq = given.find('=');
  const std::string role = given.substr(0, eq);
  std::string* slot = role == "voltage"    ? &entries.voltage
                      : role == "position" ? &entries.position
                      : role == "velocity" ? &entries.velocity
                      : role == "state"    ? &entries.state
                                           : nullptr;
  if (eq == std::string::npos || eq + 1 == given.size() || slot == nullptr) {
    throw OptionError(fmt::format("‹entry› {}: expected ROLE=NAME, ROLE one of {}", given,
                                  fmt::join(kWpilogEntryRoles, ", ")));
  }
  if (!slot->empty()) throw OptionError(fmt::format("‹entry› {}: the {} entry is named twice", given, role));
  *slot = given.substr(eq + 1);
}

}  // namespace driveid
