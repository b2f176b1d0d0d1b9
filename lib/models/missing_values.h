// The message for parameter-file values a run needs and the file does not
// give: every one named at once, with the lines to add to the section, so a
// user fixes the file in one edit rather than one value per run.
#pragma once

#include <string>
#include <vector>

#include "core/errors.h"
#include "models/parameter_table.h"

namespace driveid {

/// One line: "<where>: joint.link_inertia and joint.damping are needed <why>;
/// add to the joint section<remedy>: 'link_inertia: <value>' (link inertia
/// [kg m^2]), 'damping: <value>' (...)". Empty `missing`: logic error.
InputError MissingValuesError(const std::string& where, const std::string& section_name,
                              const std::vector<const ParameterSpec*>& missing, const std::string& why,
                              const std::string& remedy = "");

/// The model parameters (rows with a model member) of `section` not given,
/// except `zero_unless_given` (terms such as gravity that are 0 when absent).
template <class Section, class Model>
std::vector<const ParameterSpec*> MissingModelValues(const ParameterTable<Section, Model>& table,
                                                     const Section& section,
                                                     const std::vector<std::string>& zero_unless_given = {}) {
  std::vector<const ParameterSpec*> missing;
  for (const auto& row : table) {
    if (std::find(zero_unless_given.begin(), zero_unless_given.end(), row.spec.key) != zero_unless_given.end()) continue;
    if (row.is_model() && !SectionValue(row, section)) missing.push_back(&row.spec);
  }
  return missing;
}

/// Throws MissingValuesError "<where>: ... needed by <purpose>" naming every
/// model parameter of `section` not given (except `zero_unless_given`).
template <class Section, class Model>
void RequireModelValues(const ParameterTable<Section, Model>& table, const Section& section, const std::string& where,
                        const char* section_name, const std::string& purpose,
                        const std::vector<std::string>& zero_unless_given = {}) {
  const auto missing = MissingModelValues(table, section, zero_unless_given);
  if (!missing.empty()) throw MissingValuesError(where, section_name, missing, "by " + purpose);
}

}  // namespace driveid
