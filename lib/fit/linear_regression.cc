#include "fit/linear_regression.h"

#include <stdexcept>

#include <Eigen/Core>
#include <fmt/format.h>

#include "fit/linear_residuals.h"

namespace driveid {

LinearRegression::LinearRegression(std::vector<std::string> columns) : columns_(std::move(columns)) {}

std::size_t LinearRegression::column(const std::string& name) const {
  for (std::size_t j = 0; j < columns_.size(); ++j) {
    if (columns_[j] == name) return j;
  }
  throw std::logic_error(fmt::format("LinearRegression: no column '{}'", name));
}

void LinearRegression::Reserve(std::size_t rows) {
  regressor_.reserve(rows * columns_.size());
  measured_.reserve(rows);
  known_.reserve(rows);
}

void LinearRegression::BeginChannel(const std::string& name) { channels_.push_back({name, rows()}); }

void LinearRegression::AddRow(const std::vector<double>& regressor, double measured, double known) {
  if (regressor.size() != columns_.size() || channels_.empty()) {
    throw std::logic_error("LinearRegression::AddRow: row size differs from the columns, or no channel begun");
  }
  regressor_.insert(regressor_.end(), regressor.begin(), regressor.end());
  measured_.push_back(measured);
  known_.push_back(known);
}

FitResult LinearRegression::Fit(const std::vector<FitParameter>& free, const std::map<std::string, double>& fixed,
                                 const FitOptions& options) const {
  const std::size_t n = rows(), m = columns_.size();
  std::vector<std::size_t> free_index;
  for (const auto& parameter : free) free_index.push_back(column(parameter.name));
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
  std::vector<FitChannel> channels;
  for (std::size_t c = 0; c < channels_.size(); ++c) {
    const std::size_t end = c + 1 < channels_.size() ? channels_[c + 1].begin : n;
    if (end == channels_[c].begin) continue;
    channels.push_back({channels_[c].name, static_cast<int>(channels_[c].begin), static_cast<int>(end - channels_[c].begin),
                        measured_.data() + channels_[c].begin});
  }
  LinearResiduals residuals(regressor_.data(), m, std::move(free_index), std::move(y));
  return FitLeastSquares(residuals, free, channels, options);
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
