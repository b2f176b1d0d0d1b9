// Parameter files (docs/formats.md): YAML with one section per model, plain
// values a controller can read, and a separate `fit` section with the
// statistics and provenance written by the fitting commands. Each section is
// read and written from its model's parameter table (models/*.h).
//
// Reading is strict: unknown keys, duplicate keys, non-numbers, NaN/Inf and
// out-of-range values throw InputError "file:line:column: section.key: what".
// Keys that are absent (or written without a value) are not given.
#pragma once

#include <any>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "control/cdrive_control_settings.h"
#include "core/fit_result.h"
#include "models/axis.h"
#include "models/cdrive.h"
#include "models/drivetrain.h"
#include "models/feedback.h"
#include "models/feedforward.h"
#include "models/frequency_response.h"
#include "models/joint.h"
#include "models/planar_robot.h"
#include "params/parameter_numbers.h"

namespace driveid {

/// A parameter file: the sections of the models it holds (each section
/// struct names itself with `kSectionName` and is registered once, by its
/// file: params/parameter_sections.h), plus what a previous fit left.
class ParameterFile {
 public:
  /// The section of type S, or nullptr when the file has none.
  template <class S>
  const S* Find() const {
    const auto it = sections_.find(S::kSectionName);
    return it == sections_.end() ? nullptr : std::any_cast<S>(&it->second);
  }
  template <class S>
  S* Find() {
    const auto it = sections_.find(S::kSectionName);
    return it == sections_.end() ? nullptr : std::any_cast<S>(&it->second);
  }
  /// Adds or replaces the section of type S.
  template <class S>
  void Set(S section) {
    sections_[S::kSectionName] = std::move(section);
  }

  bool had_fit_section = false;  ///< input carried a previous fit (replaced on output)
  /// That fit section as written (from its line "fit:" to the next top-level
  /// key), kept by a writer that makes no fit of its own (e.g. `gains`).
  std::string fit_text;
  /// fit.estimates of a previous fit (value, std, ci95), for reports.
  std::vector<ParameterEstimate> fit_estimates;
  /// fit.rmse and fit.inflation of a previous fit, per channel ("log:tau"),
  /// for a design that predicts from the noise the fit met.
  std::vector<std::pair<std::string, double>> fit_rmse, fit_inflation;
  /// Feed-forward gains (docs/models.md#feed-forward), written by the axis
  /// fit; none when `gains` is empty.
  Feedforward feedforward;
  /// Feedback controller (docs/models.md#feedback-gains), written by
  /// `gains`; none when its loop is empty.
  FeedbackController feedback;
  /// fit.correlation of a previous fit: pairs of estimate names and their
  /// correlation (the full matrix or the strongest pairs, as written).
  std::vector<std::pair<std::pair<std::string, std::string>, double>> fit_correlations;
  /// The correlation of estimates a and b in fit_correlations (1 for a == b,
  /// 0 where the file holds none).
  double FitCorrelation(const std::string& a, const std::string& b) const {
    if (a == b) return 1.0;
    for (const auto& [names, r] : fit_correlations) {
      if ((names.first == a && names.second == b) || (names.first == b && names.second == a)) return r;
    }
    return 0.0;
  }

 private:
  std::map<std::string, std::any> sections_;
};

/// Parses YAML text; `path` is used in messages only.
ParameterFile ParseParameterFile(const std::string& path, const std::string& text);
/// Reads and parses a file.
ParameterFile ReadParameterFile(const std::string& path);

/// Formats a parameter file; with `fit`/`provenance` non-null a `fit`
/// section is added; with both null, the read file's own (`fit_text`) is
/// kept as it was. Output is deterministic and reads back unchanged.
std::string FormatParameterFile(const ParameterFile& file, const FitResult* fit = nullptr,
                                const FitProvenance* provenance = nullptr,
                                const std::vector<DerivedQuantity>& derived = {});

}  // namespace driveid
