// One design for the inverse-dynamics fits (axis, C-drive, robot): a linear
// model y = X p over named regressor columns, built row by row by a fit's
// row builder and owning its data. Each row belongs to a measured channel
// (RMSE and fit % are of what was measured). Columns that are not estimated
// are fixed at known values and subtracted from y, as is a per-row part
// known from outside the columns.
// Documented in docs/models.md#identification.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/fit_result.h"
#include "fit/core/least_squares.h"

namespace driveid {

class LinearRegression {
 public:
  /// The regressor columns, by the names their parameters have in the fit.
  explicit LinearRegression(std::vector<std::string> columns);

  const std::vector<std::string>& columns() const { return columns_; }
  /// Index of a column; throws std::logic_error for an unknown name.
  std::size_t column(const std::string& name) const;

  /// Room for `rows` rows in all (a builder that knows its count avoids
  /// regrowing the design, which briefly holds it twice).
  void Reserve(std::size_t rows);
  /// Starts a measured channel: the rows added next belong to it.
  void BeginChannel(const std::string& name);
  /// Appends a row: `regressor` has one value per column; `measured` is the
  /// measured value; `known` a part of it from outside the columns.
  void AddRow(const std::vector<double>& regressor, double measured, double known = 0.0);

  std::size_t rows() const { return measured_.size(); }
  double at(std::size_t row, std::size_t column) const {
    return design_(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(column));
  }
  double measured(std::size_t row) const { return measured_[row]; }
  /// First row of each channel, in order (channels without rows included).
  std::vector<std::size_t> channel_begins() const {
    std::vector<std::size_t> begins;
    for (const auto& c : channels_) begins.push_back(c.begin);
    return begins;
  }

  /// Fits the columns named in `free` (in that order); every other column is
  /// fixed at `fixed` (which must hold it). Channels without rows are left out.
  FitResult Fit(const std::vector<FitParameter>& free, const std::map<std::string, double>& fixed,
                const FitOptions& options) const;

  /// The same, for a fit whose design is not needed afterwards: a large one
  /// (FitOptions::large) is solved exactly on the normal
  /// equations (FitLinearLeastSquares) with the design itself as the
  /// Jacobian when every column is free, in order; the rows are gone after.
  FitResult FitAndRelease(const std::vector<FitParameter>& free, const std::map<std::string, double>& fixed,
                          const FitOptions& options);

  /// A copy with more columns: `names`, and for each its value at every row
  /// (`values[c][row]`); the rows, channels and known parts the same.
  LinearRegression WithColumns(const std::vector<std::string>& names,
                               const std::vector<std::vector<double>>& values) const;

  /// The model at each row for column values `values` (all columns), known part included.
  std::vector<double> Predict(const std::map<std::string, double>& values) const;

 private:
  struct Channel {
    std::string name;
    std::size_t begin = 0;
  };
  std::vector<std::string> columns_;
  // The first rows() rows hold the regressors (more are room to grow).
  RowMatrix design_;
  // y = measured - known - fixed columns, and the channels for the fit core.
  Eigen::VectorXd Target(const std::vector<std::size_t>& free_index, const std::map<std::string, double>& fixed) const;
  std::vector<FitChannel> FitChannels() const;
  std::vector<std::size_t> FreeIndex(const std::vector<FitParameter>& free) const;
  std::vector<double> measured_;
  std::vector<double> known_;
  std::vector<Channel> channels_;
};

}  // namespace driveid
