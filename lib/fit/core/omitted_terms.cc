#include "fit/core/omitted_terms.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <boost/math/distributions/chi_squared.hpp>

#include "fit/core/least_squares.h"

namespace driveid {

OmittedTermTest TestOmittedTerm(const LinearRegression& regression, const std::vector<std::string>& free,
                                const std::map<std::string, double>& values, const std::string& term,
                                const std::vector<std::string>& columns, double min_share) {
  OmittedTermTest out;
  out.term = term;
  out.coefficients.assign(columns.size(), 0.0);
  const auto n = static_cast<Eigen::Index>(regression.rows());
  const auto p = static_cast<Eigen::Index>(free.size());
  const auto k = static_cast<Eigen::Index>(columns.size());
  if (n <= p + k || k == 0) return out;
  RowMatrix x(n, p), z(n, k);
  for (Eigen::Index c = 0; c < p; ++c) {
    const std::size_t j = regression.column(free[static_cast<std::size_t>(c)]);
    for (Eigen::Index r = 0; r < n; ++r) x(r, c) = regression.at(static_cast<std::size_t>(r), j);
  }
  for (Eigen::Index c = 0; c < k; ++c) {
    const std::size_t j = regression.column(columns[static_cast<std::size_t>(c)]);
    for (Eigen::Index r = 0; r < n; ++r) z(r, c) = regression.at(static_cast<std::size_t>(r), j);
  }
  const std::vector<double> model = regression.Predict(values);
  Eigen::VectorXd e(n);
  for (Eigen::Index r = 0; r < n; ++r) e(r) = regression.measured(static_cast<std::size_t>(r)) - model[static_cast<std::size_t>(r)];
  const double ee = e.squaredNorm();
  if (!(ee > 0.0)) return out;
  // Z~ = Z - X (X'X)^-1 X'Z through a rank-revealing QR of X.
  if (p > 0) {
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr_x(x);
    z -= x * qr_x.solve(Eigen::MatrixXd(z));
  }
  // Keep the columns the fit does not already span (the projection leaves
  // more than 1e-6 of their norm), independent of each other.
  std::vector<Eigen::Index> kept;
  for (Eigen::Index c = 0; c < k; ++c) {
    double original = 0.0;
    const std::size_t j = regression.column(columns[static_cast<std::size_t>(c)]);
    for (Eigen::Index r = 0; r < n; ++r) original += std::pow(regression.at(static_cast<std::size_t>(r), j), 2);
    if (z.col(c).squaredNorm() > 1e-12 * original && original > 0.0) kept.push_back(c);
  }
  if (kept.empty()) return out;
  RowMatrix zk(n, static_cast<Eigen::Index>(kept.size()));
  for (std::size_t c = 0; c < kept.size(); ++c) zk.col(static_cast<Eigen::Index>(c)) = z.col(kept[c]);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr_z(zk);
  if (qr_z.rank() < zk.cols()) return out;
  const Eigen::VectorXd g = qr_z.solve(e);
  for (std::size_t c = 0; c < kept.size(); ++c) out.coefficients[static_cast<std::size_t>(kept[c])] = g(static_cast<Eigen::Index>(c));
  const Eigen::VectorXd u = e - zk * g;
  const Eigen::MatrixXd zz = zk.transpose() * zk;
  const Eigen::MatrixXd zz_inverse = zz.inverse();
  // Long-run covariance of Z~'u per channel, summed (channels independent).
  Eigen::MatrixXd middle = Eigen::MatrixXd::Zero(zk.cols(), zk.cols());
  const std::vector<std::size_t> begins = regression.channel_begins();
  for (std::size_t c = 0; c < begins.size(); ++c) {
    const auto begin = static_cast<Eigen::Index>(begins[c]);
    const auto end = c + 1 < begins.size() ? static_cast<Eigen::Index>(begins[c + 1]) : n;
    if (end <= begin) continue;
    middle += CalcLongRunCovariance(zk.middleRows(begin, end - begin), u.segment(begin, end - begin)).covariance;
  }
  const Eigen::MatrixXd covariance = zz_inverse * middle * zz_inverse;
  out.dof = static_cast<int>(zk.cols());
  out.wald = g.dot(covariance.ldlt().solve(g));
  out.share = std::clamp(e.dot(zk * g) / ee, 0.0, 1.0);
  const boost::math::chi_squared distribution(out.dof);
  out.critical = boost::math::quantile(distribution, 0.999);
  out.missing = std::isfinite(out.wald) && out.wald > out.critical && out.share >= min_share;
  return out;
}

}  // namespace driveid
