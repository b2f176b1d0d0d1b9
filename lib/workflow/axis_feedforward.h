// Feed-forward gains of a fitted axis (models/feedforward.h,
// docs/models.md#feed-forward) with standard errors propagated from the
// fit's covariance.
#pragma once

#include <string>

#include "core/fit_result.h"
#include "models/axis.h"
#include "models/feedforward.h"
#include "report/feedforward_report.h"

namespace driveid {

/// Standard error of a derived value from the gradient of the value with
/// respect to the fit's estimates (by name; parameters the fit held fixed
/// contribute nothing): sqrt(g' C g), first order.
double PropagateStandardError(const FitResult& fit, const std::vector<std::pair<std::string, double>>& gradient);

/// The gains of the axis `p` fitted as `fit`. Ka only with `with_inertia`
/// (an inertia that was fitted or given, not a default 0); direction pairs
/// where the direction-dependent terms were fitted or are non-zero; Kg and
/// Kg_angle where the gravity terms were; the offset where fitted or non-zero.
Feedforward CalcAxisFeedforward(const AxisParameters& p, const FitResult& fit, const std::string& effort_unit,
                                const std::string& position_unit, bool with_inertia);

}  // namespace driveid
