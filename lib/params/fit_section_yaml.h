// The parameter file's `fit` section (core/fit_section.h: its keys), as
// YAML: estimates with std and interval, derived values, correlations,
// the channels' statistics and the provenance, and read back for reports,
// designs and propagated std.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "core/fit_result.h"

namespace driveid {

/// What a previous fit left that is read back (ParameterFile's fit_* fields).
struct PreviousFit {
  std::vector<ParameterEstimate> estimates;
  std::vector<std::pair<std::string, double>> rmse, inflation;
  std::vector<std::pair<std::pair<std::string, std::string>, double>> correlations;
};

/// Reads the section `fit`.
PreviousFit ParseFitSection(const std::string& path, const YAML::Node& node);
/// The text of the top-level section `fit` as written in `text` (from its
/// key's line to the next top-level key); "" when it would not read back alone.
std::string FitSectionText(const std::string& text, const YAML::Node& root);
/// The section `fit` of a fit and its provenance.
std::string FormatFitSection(const FitResult& fit, const FitProvenance& provenance,
                             const std::vector<DerivedQuantity>& derived);

}  // namespace driveid
