#include "fit/core/linear_regression.h"

#include <algorithm>
#include <stdexcept>

#include <Eigen/Core>
#include <fmt/format.h>

#include "fit/core/fit_statistics.h"
#include "fit/core/linear_residuals.h"
#include "fit/core/scaled_cost.h"

namespace driveid {

LinearRegression::LinearRegression(std::vector<std::string> columns) : columns_(std::move(columns)) {}

std::size_t LinearRegression::column(const std::string& name) const {
  for (std::size_t j = 0; j < columns_.size(); ++j) {
    if (columns_[j] == name) return j;
  }
  throw std::logic_error(fmt::format("LinearRegression: no column '{}'", name));
}

void LinearRegression::Reserve(std::size_t rows) {
  if (static_cast<Eigen::Index>(rows) > design_.rows()) {
    design_.conservativeResize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(columns_.size()));
  }
  measured_.reserve(rows);
  known_.reserve(rows);
}

void LinearRegression::BeginChannel(const std::string& name) { channels_.push_back({name, rows()}); }

LinearRegression LinearRegression::WithColumns(const std::vector<std::string>& names,
                                               const std::vector<std::vector<double>>& values) const {
  if (names.size() != values.size()) throw std::logic_error("LinearRegression::WithColumns: names and values differ");
  for (const auto& v : values) {
    if (v.size() != rows()) throw std::logic_error("LinearRegression::WithColumns: a column's length is not rows()");
  }
  std::vector<std::string> columns = columns_;
  columns.insert(columns.end(), names.begin(), names.end());
  LinearRegression out(std::move(columns));
  out.Reserve(rows());
  std::size_t channel = 0;
  std::vector<double> row(out.columns_.size());
  for (std::size_t r = 0; r < rows(); ++r) {
    while (channel < channels_.size() && channels_[channel].begin == r) out.BeginChannel(channels_[channel++].name);
    for (std::size_t j = 0; j < columns_.size(); ++j) row[j] = at(r, j);
    for (std::size_t c = 0; c < names.size(); ++c) row[columns_.size() + c] = values[c][r];
    out.AddRow(row, measured_[r], known_[r]);
  }
  while (channel < channels_.size()) out.BeginChannel(channels_[channel++].name);
  return out;
}

void LinearRegression::AddRow(const std::vector<double>& regressor, double measured, double known) {
  if (regressor.size() != columns_.size() || channels_.empty()) {
    throw std::logic_error("LinearRegression::AddRow: row size differs from the columns, or no channel begun");
  }
  const auto row = static_cast<Eigen::Index>(rows());
  // Geometric growth (amortised O(1) per row) for builders that cannot count
  // their rows ahead; those that can call Reserve once.
  if (row == design_.rows()) Reserve(std::max<std::size_t>(64, 2 * rows()));
  for (std::size_t j = 0; j < regressor.size(); ++j) design_(row, static_cast<Eigen::Index>(j)) = regressor[j];
  measured_.push_back(measured);
  known_.push_back(known);
}

std::vector<std::size_t> LinearRegression::FreeIndex(const std::vector<FitParameter>& free) const {
  std::vector<std::size_t> index;
  for (const auto& parameter : free) index.push_back(column(parameter.name));
  return index;
}

Eigen::VectorXd LinearRegression::Target(const std::vector<std::size_t>& free_index,
                                         const std::map<std::string, double>& fixed) const {
  // y = measured - known - sum over fixed columns of value x column: the
  // free parameters are fitted to what the fixed ones leave.
  const std::size_t n = rows(), m = columns_.size();
  std::vector<std::pair<std::size_t, double>> fixed_terms;
  for (std::size_t j = 0; j < m; ++j) {
    bool is_free = false;
    for (std::size_t f : free_index) is_free = is_free || f == j;
    if (is_free) continue;
    const auto value = fixed.find(columns_[j]);
    if (value == fixed.end()) throw std::logic_error(fmt::format("LinearRegression::Fit: no value for '{}'", columns_[j]));
    if (value->second != 0.0) fixed_terms.emplace_back(j, value->second);
  }
  Eigen::VectorXd y(static_cast<Eigen::Index>(n));
  for (std::size_t r = 0; r < n; ++r) {
    double known = known_[r];
    for (const auto& [j, value] : fixed_terms) known += value * at(r, j);
    y(static_cast<Eigen::Index>(r)) = measured_[r] - known;
  }
  return y;
}

std::vector<FitChannel> LinearRegression::FitChannels() const {
  std::vector<FitChannel> channels;
  for (std::size_t c = 0; c < channels_.size(); ++c) {
    const std::size_t end = c + 1 < channels_.size() ? channels_[c + 1].begin : rows();
    if (end == channels_[c].begin) continue;
    channels.push_back({channels_[c].name, static_cast<int>(channels_[c].begin), static_cast<int>(end - channels_[c].begin),
                        measured_.data() + channels_[c].begin});
  }
  return channels;
}

FitResult LinearRegression::Fit(const std::vector<FitParameter>& free, const std::map<std::string, double>& fixed,
                                 const FitOptions& options) const {
  std::vector<std::size_t> free_index = FreeIndex(free);
  Eigen::VectorXd y = Target(free_index, fixed);
  LinearResiduals residuals(design_.data(), columns_.size(), std::move(free_index), std::move(y));
  return FitLeastSquares(residuals, free, FitChannels(), options);
}

FitResult LinearRegression::FitAndRelease(const std::vector<FitParameter>& free,
                                          const std::map<std::string, double>& fixed, const FitOptions& options) {
  const std::size_t n = rows(), p = free.size();
  if (!options.large.IsLarge(n, p)) {
    FitResult result = Fit(free, fixed, options);
    *this = LinearRegression(columns_);
    return result;
  }
  // A large design (a long log of a whole arm) is handed to the solver
  // instead of copied: when every column is free and in order the design
  // matrix itself becomes the Jacobian block, so peak memory stays one
  // design, not two.
  const std::vector<std::size_t> free_index = FreeIndex(free);
  const Eigen::VectorXd y = Target(free_index, fixed);
  JacobianBlock block;
  bool in_order = p == columns_.size();
  for (std::size_t c = 0; c < p && in_order; ++c) in_order = free_index[c] == c;
  if (in_order) {
    design_.conservativeResize(static_cast<Eigen::Index>(n), design_.cols());  // no copy when reserved exactly
    block.values = std::move(design_);
  } else {
    block.values.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(p));
    for (std::size_t r = 0; r < n; ++r) {
      for (std::size_t c = 0; c < p; ++c) block.values(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = at(r, free_index[c]);
    }
  }
  design_ = RowMatrix();
  known_ = {};
  for (std::size_t j = 0; j < p; ++j) block.columns.push_back(static_cast<int>(j));
  // The channels point into measured_, which stays until the statistics are done.
  FitResult result = FitLinearLeastSquares(std::move(block), y, free, FitChannels(), options);
  *this = LinearRegression(columns_);
  return result;
}

std::vector<double> LinearRegression::Predict(const std::map<std::string, double>& values) const {
  std::vector<double> coefficient(columns_.size());
  for (std::size_t j = 0; j < columns_.size(); ++j) {
    const auto value = values.find(columns_[j]);
    if (value == values.end()) throw std::logic_error(fmt::format("LinearRegression::Predict: no value for '{}'", columns_[j]));
    coefficient[j] = value->second;
  }
  std::vector<double> model(rows());
  for (std::size_t r = 0; r < rows(); ++r) {
    double sum = known_[r];
    for (std::size_t j = 0; j < columns_.size(); ++j) sum += coefficient[j] * at(r, j);
    model[r] = sum;
  }
  return model;
}

}  // namespace driveid
