// One parameter table per model, declared beside the model struct: key,
// paper symbol, unit, bound, default free set and where the value lives.
// The parameter-file reader and writer, `--free` validation and help texts,
// the fits' start values, bounds and scales, and the reports all read it, so
// a key is written down once (docs/adding-a-model.md).
//
// A model has two structs: its file section (`std::optional` per key: given
// or not, as the user wrote it) and its parameters (plain doubles the
// equations use). A row points into both; settings that are not model
// parameters (a torque constant, a gear ratio used for reporting) point into
// the section only.
#pragma once

#include <algorithm>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "core/errors.h"

namespace driveid {

/// What a parameter is, independent of where it is stored.
struct ParameterSpec {
  const char* key;          ///< parameter-file key and --free name
  const char* symbol;       ///< the paper's symbol (ASCII)
  const char* unit;         ///< SI unit, e.g. "N m s/rad"
  const char* description;  ///< what it is
  double lower_bound = 0.0;             ///< physical bound
  bool lower_exclusive = false;         ///< value must be > lower_bound (else >=)
  bool required = false;                ///< the section is incomplete without it
  const char* fit = "";                 ///< fit that estimates it ("" = none); several: "a b"
  bool default_free = false;            ///< in that fit's default --free set
  double typical = 0.0;                 ///< typical magnitude for scaling (0 = from the start value)

  // Table rows name their fields (Spec(...).Above(0).Required().Fit("step")):
  /// Value must be > `bound`.
  constexpr ParameterSpec Above(double bound) const { return With(bound, true, required, fit, default_free, typical); }
  /// Value must be >= `bound` (the default bound is >= 0).
  constexpr ParameterSpec AtLeast(double bound) const { return With(bound, false, required, fit, default_free, typical); }
  /// Any finite value.
  constexpr ParameterSpec Unbounded() const {
    return With(-std::numeric_limits<double>::infinity(), false, required, fit, default_free, typical);
  }
  /// The section is incomplete without it.
  constexpr ParameterSpec Required() const {
    return With(lower_bound, lower_exclusive, true, fit, default_free, typical);
  }
  /// Estimated by the named fit(s) ("a b": several).
  constexpr ParameterSpec Fit(const char* fits) const {
    return With(lower_bound, lower_exclusive, required, fits, default_free, typical);
  }
  /// In that fit's default free set.
  constexpr ParameterSpec FreeByDefault() const {
    return With(lower_bound, lower_exclusive, required, fit, true, typical);
  }
  /// Typical magnitude for scaling.
  constexpr ParameterSpec Typical(double value) const {
    return With(lower_bound, lower_exclusive, required, fit, default_free, value);
  }

  /// "description [unit]" as written beside a value in a parameter file.
  std::string Doc() const { return fmt::format("{} [{}]", description, unit); }
  /// True when `value` satisfies the bound.
  bool Admits(double value) const { return lower_exclusive ? value > lower_bound : value >= lower_bound; }
  /// True when the named fit estimates this parameter.
  bool InFit(const std::string& name) const {
    const std::string fits = std::string(" ") + fit + " ";
    return !name.empty() && fits.find(" " + name + " ") != std::string::npos;
  }

 private:
  constexpr ParameterSpec With(double bound, bool exclusive, bool needed, const char* fits, bool free,
                               double magnitude) const {
    return {key, symbol, unit, description, bound, exclusive, needed, fits, free, magnitude};
  }
};

/// A table row's spec: key, the paper's symbol, unit and description; then
/// named fields (Above, AtLeast, Unbounded, Required, Fit, FreeByDefault,
/// Typical). Default: >= 0, optional, in no fit.
constexpr ParameterSpec Spec(const char* key, const char* symbol, const char* unit, const char* description) {
  return {key, symbol, unit, description, 0.0, false, false, "", false, 0.0};
}

constexpr double kUnbounded = -std::numeric_limits<double>::infinity();

/// A row of a model's table: the spec, the value in the file section and
/// (nullptr for settings) in the model's parameter struct. A term added to
/// a model without a member of its own (models/axis_term.h) stores its
/// parameters by position instead: `slot` indexes the section's and the
/// model's `extra` arrays (ModelValue, SectionValue reach either).
template <class Section, class Model>
struct ParameterRow {
  ParameterSpec spec;
  std::optional<double> Section::*in_section;
  double Model::*in_model;
  int slot = -1;
  /// A model parameter (the equations use it), not a setting.
  bool is_model() const { return in_model != nullptr || slot >= 0; }
};

/// True for a model (or section) struct with `extra` slots.
template <class T, class = void>
struct HasExtraSlots : std::false_type {};
template <class T>
struct HasExtraSlots<T, std::void_t<decltype(std::declval<T&>().extra)>> : std::true_type {};

/// The value a model row stores in `model` (its member or its slot).
template <class Section, class Model>
double& ModelValue(const ParameterRow<Section, Model>& row, Model& model) {
  if constexpr (HasExtraSlots<Model>::value) {
    if (row.slot >= 0) return model.extra[static_cast<std::size_t>(row.slot)];
  }
  return model.*(row.in_model);
}
template <class Section, class Model>
double ModelValue(const ParameterRow<Section, Model>& row, const Model& model) {
  return ModelValue(row, const_cast<Model&>(model));
}

/// The value a row stores in `section` (its member or its slot).
template <class Section, class Model>
std::optional<double>& SectionValue(const ParameterRow<Section, Model>& row, Section& section) {
  if constexpr (HasExtraSlots<Section>::value) {
    if (row.slot >= 0) return section.extra[static_cast<std::size_t>(row.slot)];
  }
  return section.*(row.in_section);
}
template <class Section, class Model>
const std::optional<double>& SectionValue(const ParameterRow<Section, Model>& row, const Section& section) {
  return SectionValue(row, const_cast<Section&>(section));
}

template <class Section, class Model>
using ParameterTable = std::vector<ParameterRow<Section, Model>>;

/// The row of `key`, or nullptr.
template <class Section, class Model>
const ParameterRow<Section, Model>* FindParameter(const ParameterTable<Section, Model>& table, const std::string& key) {
  for (const auto& row : table) {
    if (key == row.spec.key) return &row;
  }
  return nullptr;
}

/// The key of the model parameter stored in `member` (so that code naming a
/// parameter refers to the table, not to a restated string).
template <class Section, class Model>
std::string KeyOf(const ParameterTable<Section, Model>& table, double Model::*member) {
  for (const auto& row : table) {
    if (row.in_model == member) return row.spec.key;
  }
  throw std::logic_error("KeyOf: member not in the table");
}

/// The spec of the row stored in the section member `member` (settings too).
template <class Section, class Model>
const ParameterSpec& SpecOf(const ParameterTable<Section, Model>& table, std::optional<double> Section::*member) {
  for (const auto& row : table) {
    if (row.in_section == member) return row.spec;
  }
  throw std::logic_error("SpecOf: member not in the table");
}

/// Keys a fit estimates (all of them, or only its default --free set).
template <class Section, class Model>
std::vector<std::string> FitParameterKeys(const ParameterTable<Section, Model>& table, const std::string& fit,
                                          bool default_only = false) {
  std::vector<std::string> keys;
  for (const auto& row : table) {
    if (row.spec.InFit(fit) && (!default_only || row.spec.default_free)) keys.push_back(row.spec.key);
  }
  return keys;
}

/// Throws OptionError unless every name is a parameter of `fit`.
template <class Section, class Model>
void CheckFreeNames(const ParameterTable<Section, Model>& table, const std::string& fit,
                    const std::vector<std::string>& names, const std::vector<std::string>& extra = {}) {
  std::vector<std::string> known = FitParameterKeys(table, fit);
  known.insert(known.end(), extra.begin(), extra.end());
  for (const auto& name : names) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      throw OptionError(
          fmt::format("‹free› {}: not a parameter of the {} fit (choose from {})", name, fit, fmt::join(known, ", ")));
    }
  }
}

/// The model parameters of a section: given values over `defaults`; throws
/// InputError naming `section_name.key` for a required value not given or a
/// value out of bounds (the model's constructor check).
template <class Section, class Model>
Model MakeModelParameters(const ParameterTable<Section, Model>& table, const Section& section, Model defaults,
                          const char* section_name) {
  for (const auto& row : table) {
    const std::optional<double>& value = SectionValue(row, section);
    if (value) {
      if (!row.spec.Admits(*value)) {
        throw InputError(fmt::format("{}.{}: must be {} {}, got {} ({})", section_name, row.spec.key,
                                     row.spec.lower_exclusive ? ">" : ">=", row.spec.lower_bound, *value,
                                     row.spec.Doc()));
      }
      if (row.is_model()) ModelValue(row, defaults) = *value;
    } else if (row.spec.required) {
      throw InputError(fmt::format("{}.{}: missing value ({})", section_name, row.spec.key, row.spec.Doc()));
    }
  }
  return defaults;
}

/// The model parameters of a section with `fill` where a value is not given
/// (no bounds checked: a prior or a simulation takes the file as it is).
template <class Section, class Model>
Model ModelValuesOr(const ParameterTable<Section, Model>& table, const Section& section, double fill) {
  Model model{};
  for (const auto& row : table) {
    if (row.is_model()) ModelValue(row, model) = SectionValue(row, section).value_or(fill);
  }
  return model;
}

/// The model parameters of a section with NaN where a value is not given
/// (for reports that show "-" and fits that tell given from missing).
template <class Section, class Model>
Model ModelValuesOrNaN(const ParameterTable<Section, Model>& table, const Section& section) {
  return ModelValuesOr(table, section, std::numeric_limits<double>::quiet_NaN());
}

/// Writes every model parameter of `model` into `section` (settings stay).
template <class Section, class Model>
void StoreModelParameters(const ParameterTable<Section, Model>& table, const Model& model, Section& section) {
  for (const auto& row : table) {
    if (row.is_model()) SectionValue(row, section) = ModelValue(row, model);
  }
}

}  // namespace driveid

namespace driveid {

/// A section with every model parameter of `model` given (settings not given).
template <class Section, class Model>
Section MakeSection(const ParameterTable<Section, Model>& table, const Model& model) {
  Section section{};
  StoreModelParameters(table, model, section);
  return section;
}

}  // namespace driveid
