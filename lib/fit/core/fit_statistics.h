// Statistics of a least-squares fit from its Jacobian and residuals at a
// point (docs/models.md#identification): the identifiability analysis of
// the column-normalised Jacobian and the robust covariance with intervals.
// The Jacobian comes in row blocks, each nonzero only in some columns (a
// log's rows in the shared parameters and its own offset), so that many
// logs with parameters of their own cost memory and time linear in their
// number; a dense Jacobian is one block with every column.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "fit/core/student_t.h"
#include "core/fit_result.h"
#include "fit/core/residual_model.h"

namespace driveid {

/// Rows [row_begin, row_begin + values.rows()) of the Jacobian, nonzero only
/// in the parameter columns `columns` (ascending), physical units.
struct JacobianBlock {
  int row_begin = 0;
  std::vector<int> columns;
  RowMatrix values;
};

/// Throws IdentificationError naming the channels when every measured channel
/// is constant (MeasurementVaries): there is nothing to identify (a torque of
/// zeros would otherwise fit every parameter as 0 +- 0).
void RequireVaryingMeasurements(const std::vector<FitChannel>& channels);

/// Throws IdentificationError naming the parameters when the normalised
/// Jacobian's columns are (nearly) collinear or dead; returns its singular
/// values (descending) otherwise. `where` is put into the message.
std::vector<double> RequireIdentifiable(const std::vector<JacobianBlock>& blocks,
                                        const std::vector<FitParameter>& parameters, const FitOptions& options,
                                        const char* where);

/// Fills estimates (from `values`), covariance, correlation, channel
/// statistics, the cost and the adequacy warnings of `result`.
/// `blocks` are taken over (normalised in place). `clusters`: see
/// FitOptions::clusters (empty: the channels' long-run covariances).
void DescribeFit(std::vector<JacobianBlock> blocks, const Eigen::VectorXd& residuals,
                 const std::vector<FitParameter>& parameters, const std::vector<double>& values,
                 const std::vector<FitChannel>& channels, FitResult& result,
                 const std::vector<std::vector<RowRange>>& clusters = {});

/// Root mean square deviation of `values` from their mean (0 for none): the
/// scale by which fits weight a channel against another of other units.
double CalcRmsDeviation(const std::vector<double>& values);

}  // namespace driveid
