// The `fit` section of a parameter file (docs/formats.md#parameter-files):
// its keys declared once, in the order the parameter file writes them. The
// writer (io/parameter_file.cc FormatParameterFile) and the JSON summary
// (report/fit_summary.cc FitJson) walk this table and switch on the key, so
// a key added here is written by both (the compiler names a switch that
// misses it); the reader (ParseParameterFile) accepts these keys and no
// other, and the records inside them by the key lists below.
#pragma once

#include <array>
#include <cstddef>

namespace driveid {

enum class FitKey {
  kCommand,          ///< the exact command line
  kVersion,          ///< the tool's version
  kModel,            ///< the model variant
  kData,             ///< one record per log: kFitDataKeys
  kEstimates,        ///< per parameter: kFitEstimateKeys
  kDerived,          ///< derived quantities: kFitDerivedKeys
  kCorrelation,      ///< of the estimates
  kRmse,             ///< per channel
  kFitPercent,       ///< per channel
  kAutocorrelation,  ///< residual lag-1, per channel
  kInflation,        ///< std with / without the residuals' correlation, per channel
  kSingularValues,   ///< of the column-normalised Jacobian
  kIterations,
  kConverged,
};

inline constexpr std::array<FitKey, 14> kFitSectionKeys = {
    FitKey::kCommand,     FitKey::kVersion,         FitKey::kModel,     FitKey::kData,
    FitKey::kEstimates,   FitKey::kDerived,         FitKey::kCorrelation, FitKey::kRmse,
    FitKey::kFitPercent,  FitKey::kAutocorrelation, FitKey::kInflation, FitKey::kSingularValues,
    FitKey::kIterations,  FitKey::kConverged};

/// The key as the file and the JSON spell it.
constexpr const char* FitKeyName(FitKey key) {
  constexpr std::array<const char*, 14> kNames = {
      "command", "version",         "model",     "data",            "estimates",  "derived",   "correlation",
      "rmse",    "fit_percent",     "autocorrelation", "inflation", "singular_values", "iterations", "converged"};
  return kNames[static_cast<std::size_t>(key)];
}

/// The keys of a data record, an estimate and a derived quantity.
inline constexpr std::array<const char*, 5> kFitDataKeys = {"file", "sha256", "samples", "segment", "notes"};
inline constexpr std::array<const char*, 3> kFitEstimateKeys = {"value", "std", "ci95"};
inline constexpr std::array<const char*, 2> kFitDerivedKeys = {"value", "std"};

}  // namespace driveid
