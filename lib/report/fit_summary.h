// Text renderings of a fit's result for people (table) and programs (JSON).
// Formatting only: the caller decides where the text goes.
#pragma once

#include <string>

#include "core/fit_result.h"

namespace driveid {

/// Human-readable table: estimates with std, 95 % interval and relative
/// error, per-channel RMSE and fit %, correlations, solver status.
std::string FormatFitTable(const FitResult& fit, const FitProvenance& provenance);

/// One JSON object with the same content (deterministic key order).
std::string FormatFitJson(const FitResult& fit, const FitProvenance& provenance);

/// JSON string literal (quotes and escapes included).
std::string JsonString(const std::string& text);

/// JSON number: shortest round-trip form; non-finite values become null.
std::string JsonNumber(double value);

}  // namespace driveid
