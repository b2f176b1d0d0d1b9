#include "logs/log_options.h"

#include <fmt/format.h>

#include "core/option_check.h"
#include "models/feedforward.h"

namespace driveid {

bool LogInputOptions::IsValid(std::string* error) const {
  OptionCheck check(error);
  check.Require(NotNegative(rate), "‹rate›", rate, "rate >= 0 Hz (0: the time column)")
      .Require(!from || Finite(*from), "‹from›", from.value_or(0.0), "finite")
      .Require(!to || Finite(*to), "‹to›", to.value_or(0.0), "finite")
      .Require(!(from && to) || *from < *to, fmt::format("‹from› {} ‹to› {}: need from < to", from.value_or(0.0),
                                                         to.value_or(0.0)));
  check.Require(UnitTextProblem(position_unit).empty(),
                fmt::format("‹unit› '{}': {}", position_unit.substr(0, 64), UnitTextProblem(position_unit)));
  for (const auto& [name, expression] : columns) {
    check.Require(!name.empty() && !expression.empty(), fmt::format("‹col› '{}={}': a name and an expression", name,
                                                                    expression));
  }
  return check;
}

}  // namespace driveid
