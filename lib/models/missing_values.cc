#include "models/missing_values.h"

#include <stdexcept>

#include <fmt/format.h>

namespace driveid {

InputError MissingValuesError(const std::string& where, const std::string& section_name,
                              const std::vector<const ParameterSpec*>& missing, const std::string& why,
                              const std::string& remedy) {
  if (missing.empty()) throw std::logic_error("MissingValuesError: nothing is missing");
  std::vector<std::string> names;
  std::string lines;
  for (const ParameterSpec* spec : missing) {
    names.push_back(fmt::format("{}.{}", section_name, spec->key));
    lines += fmt::format("{}'{}: <value>' ({})", lines.empty() ? " " : ", ", spec->key, spec->Doc());
  }
  std::string list;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) list += i + 1 == names.size() ? " and " : ", ";
    list += names[i];
  }
  return InputError(fmt::format("{}: {} {} needed {}; add to the {} section{}:{}", where, list,
                                missing.size() > 1 ? "are" : "is", why, section_name, remedy, lines));
}

}  // namespace driveid
