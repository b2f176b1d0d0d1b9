// The `fit` section of a parameter file (docs/formats.md#parameter-files):
// its keys declared once, in the order the parameter file writes them. The
// writer (params/parameter_file.cc FormatParameterFile) and the JSON summary
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
  kEstimates,        ///< per parameter: the estimate record (core/estimate_record.h)
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

/// The keys in the order the file writes them, each with its spelling.
struct FitKeySpelling {
  FitKey key;
  const char* name;  ///< as the file and the JSON spell it
};
inline constexpr std::array<FitKeySpelling, 14> kFitKeyTable = {{
    {FitKey::kCommand, "command"},
    {FitKey::kVersion, "version"},
    {FitKey::kModel, "model"},
    {FitKey::kData, "data"},
    {FitKey::kEstimates, "estimates"},
    {FitKey::kDerived, "derived"},
    {FitKey::kCorrelation, "correlation"},
    {FitKey::kRmse, "rmse"},
    {FitKey::kFitPercent, "fit_percent"},
    {FitKey::kAutocorrelation, "autocorrelation"},
    {FitKey::kInflation, "inflation"},
    {FitKey::kSingularValues, "singular_values"},
    {FitKey::kIterations, "iterations"},
    {FitKey::kConverged, "converged"},
}};

/// The keys in the file's order (kFitKeyTable's).
inline constexpr std::array<FitKey, kFitKeyTable.size()> kFitSectionKeys = [] {
  std::array<FitKey, kFitKeyTable.size()> out{};
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = kFitKeyTable[i].key;
  return out;
}();

/// The key as the file and the JSON spell it.
constexpr const char* FitKeyName(FitKey key) {
  for (const auto& entry : kFitKeyTable) {
    if (entry.key == key) return entry.name;
  }
  return "";
}

/// The keys of a data record and a derived quantity (an estimate's record:
/// core/estimate_record.h).
inline constexpr std::array<const char*, 5> kFitDataKeys = {"file", "sha256", "samples", "segment", "notes"};
inline constexpr std::array<const char*, 2> kFitDerivedKeys = {"value", "std"};

}  // namespace driveid
