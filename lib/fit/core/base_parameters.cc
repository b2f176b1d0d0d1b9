#include "fit/core/base_parameters.h"

#include <cmath>
#include <stdexcept>

#include <Eigen/QR>
#include <fmt/format.h>

namespace driveid {

BaseParameters FindBaseParameters(const Eigen::MatrixXd& w, const std::vector<std::string>& names, double tolerance) {
  const Eigen::Index p = w.cols();
  if (static_cast<std::size_t>(p) != names.size()) throw std::logic_error("FindBaseParameters: one name per column");
  BaseParameters out;
  double largest = 0.0;
  for (Eigen::Index j = 0; j < p; ++j) largest = std::max(largest, w.col(j).norm());
  // Orthonormal basis of the kept columns' span.
  Eigen::MatrixXd basis(w.rows(), 0);
  std::vector<std::size_t> dependent;
  for (Eigen::Index j = 0; j < p; ++j) {
    const double norm = w.col(j).norm();
    if (!(norm > 1e-12 * largest)) {
      out.never_moved.push_back(static_cast<std::size_t>(j));
      continue;
    }
    Eigen::VectorXd r = w.col(j) / norm;
    for (int pass = 0; pass < 2; ++pass) r -= basis * (basis.transpose() * r);  // twice: Kahan's re-orthogonalisation
    if (r.norm() > tolerance) {
      basis.conservativeResize(Eigen::NoChange, basis.cols() + 1);
      basis.col(basis.cols() - 1) = r / r.norm();
      out.base.push_back(static_cast<std::size_t>(j));
    } else {
      dependent.push_back(static_cast<std::size_t>(j));
    }
  }
  const auto r = static_cast<Eigen::Index>(out.base.size());
  Eigen::MatrixXd wb(w.rows(), r), wd(w.rows(), static_cast<Eigen::Index>(dependent.size()));
  for (Eigen::Index k = 0; k < r; ++k) wb.col(k) = w.col(static_cast<Eigen::Index>(out.base[static_cast<std::size_t>(k)]));
  for (std::size_t k = 0; k < dependent.size(); ++k) wd.col(static_cast<Eigen::Index>(k)) = w.col(static_cast<Eigen::Index>(dependent[k]));
  // W_d = W_b B, exactly up to rounding: B by least squares on W_b (none
  // to solve for when every column is a base parameter: Eigen's solve of an
  // empty right-hand side offsets a null pointer).
  const Eigen::MatrixXd b = dependent.empty() ? Eigen::MatrixXd(r, 0) : Eigen::MatrixXd(wb.colPivHouseholderQr().solve(wd));
  out.regroup = Eigen::MatrixXd::Zero(r, p);
  out.combination.resize(out.base.size());
  for (Eigen::Index k = 0; k < r; ++k) {
    out.regroup(k, static_cast<Eigen::Index>(out.base[static_cast<std::size_t>(k)])) = 1.0;
    out.combination[static_cast<std::size_t>(k)].push_back({out.base[static_cast<std::size_t>(k)], 1.0});
    for (std::size_t d = 0; d < dependent.size(); ++d) {
      double c = b(k, static_cast<Eigen::Index>(d));
      // Rounding leaves ~1e-12 where the structure has 0 or a simple ratio.
      if (std::abs(c) < 1e-9) continue;
      if (std::abs(c - std::round(c)) < 1e-9) c = std::round(c);
      // The structure's coefficients are products of the URDF's lengths:
      // ten digits hold them; the rest is the solve's rounding.
      c = std::stod(fmt::format("{:.10g}", c));
      out.regroup(k, static_cast<Eigen::Index>(dependent[d])) = c;
      out.combination[static_cast<std::size_t>(k)].push_back({dependent[d], c});
    }
    out.names.push_back(CombinationName(out.combination[static_cast<std::size_t>(k)], names));
  }
  return out;
}

std::string CombinationName(const std::vector<std::pair<std::size_t, double>>& combination,
                            const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < combination.size(); ++i) {
    const auto& [column, c] = combination[i];
    const std::string& name = names.at(column);
    if (i == 0) {
      out = c == 1.0 ? name : fmt::format("{:.4g} {}", c, name);
      continue;
    }
    const char* sign = c < 0.0 ? " - " : " + ";
    out += std::abs(c) == 1.0 ? fmt::format("{}{}", sign, name) : fmt::format("{}{:.4g} {}", sign, std::abs(c), name);
  }
  return out;
}

}  // namespace driveid
