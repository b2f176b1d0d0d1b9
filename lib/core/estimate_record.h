// The record of a fitted parameter, `{value, std, ci95}` (docs/formats.md#parameter-files):
// its fields declared once, here, and visited by every archive that writes
// or reads it — the parameter file's YAML writer and reader
// (params/parameter_file.cc) and the JSON summary (report/fit_summary.cc) — in
// the manner of Drake's Serialize(Archive*). A field added here is written,
// read back and accepted by all of them.
#pragma once

#include <string>
#include <vector>

#include "core/fit_result.h"

namespace driveid {

/// How a field is stated: the value to the last bit; its standard error
/// and interval ends to six significant digits (what a std can promise).
enum class EstimateField { kValue, kStandardError };

/// Visits the record's fields in the order they are written. An archive
/// has `Scalar(key, field, double&)` and `Interval(key, double& low,
/// double& high)`; a writer takes a const ParameterEstimate.
template <class Archive, class Estimate>
void VisitEstimateRecord(Archive& archive, Estimate& e) {
  archive.Scalar("value", EstimateField::kValue, e.value);
  archive.Scalar("std", EstimateField::kStandardError, e.standard_error);
  archive.Interval("ci95", e.ci95_low, e.ci95_high);
}

/// The record's keys, in order (the reader accepts these and no other).
inline std::vector<std::string> EstimateRecordKeys() {
  struct Keys {
    std::vector<std::string> names;
    void Scalar(const char* key, EstimateField, const double&) { names.emplace_back(key); }
    void Interval(const char* key, const double&, const double&) { names.emplace_back(key); }
  } keys;
  const ParameterEstimate e;
  VisitEstimateRecord(keys, e);
  return keys.names;
}

}  // namespace driveid
