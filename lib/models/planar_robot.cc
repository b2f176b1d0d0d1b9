#include "models/planar_robot.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace driveid {

std::array<Vector2, 3> CalcBaseJoints(double a) {
  return {Vector2{0.0, 0.0}, Vector2{a, 0.0}, Vector2{0.5 * a, 0.5 * a * std::sqrt(3.0)}};
}

Vector3 CalcInverseKinematics(const PlanarRobotParameters& p, const Vector2& c) {
  const auto bases = CalcBaseJoints(p.base_distance);
  Vector3 theta = Vector3::Zero();
  for (std::size_t i = 0; i < 3; ++i) {
    const double dx = c[0] - bases[i][0], dy = c[1] - bases[i][1];
    const double distance = std::hypot(dx, dy);
    if (!(distance <= 2.0 * p.link_length) || distance == 0.0) {
      throw std::domain_error(fmt::format("leg {} cannot reach ({:.4f}, {:.4f}) m: distance {:.4f} m, reach {:.4f} m",
                                          i + 1, c[0], c[1], distance, 2.0 * p.link_length));
    }
    theta[i] = std::atan2(dy, dx) + p.elbow[i] * std::acos(distance / (2.0 * p.link_length));
  }
  return theta;
}

Vector2 CalcForwardKinematics(const PlanarRobotParameters& p, const Vector3& theta, const Vector2& guess) {
  const auto bases = CalcBaseJoints(p.base_distance);
  std::array<Vector2, 3> b{};
  for (std::size_t i = 0; i < 3; ++i) {
    b[i] = {bases[i][0] + p.link_length * std::cos(theta[i]), bases[i][1] + p.link_length * std::sin(theta[i])};
  }
  Vector2 c = guess;
  for (int iteration = 0; iteration < 20; ++iteration) {
    // r_i = (|C - B_i|^2 - l^2) / 2, gradient d_i: solve the 2 x 2 normal equations.
    double h00 = 0, h01 = 0, h11 = 0, g0 = 0, g1 = 0;
    for (std::size_t i = 0; i < 3; ++i) {
      const double dx = c[0] - b[i][0], dy = c[1] - b[i][1];
      const double r = 0.5 * (dx * dx + dy * dy - p.link_length * p.link_length);
      h00 += dx * dx;
      h01 += dx * dy;
      h11 += dy * dy;
      g0 += dx * r;
      g1 += dy * r;
    }
    const double det = h00 * h11 - h01 * h01;
    if (!(std::abs(det) > 0.0)) break;
    const double step0 = (h11 * g0 - h01 * g1) / det, step1 = (h00 * g1 - h01 * g0) / det;
    c[0] -= step0;
    c[1] -= step1;
    if (std::abs(step0) + std::abs(step1) < 1e-13) break;
  }
  return c;
}

ClosureCheck CalcClosure(const PlanarRobotParameters& p, const Vector3& theta, const Vector2& c) {
  const auto bases = CalcBaseJoints(p.base_distance);
  ClosureCheck out;
  const double l = p.link_length;
  for (std::size_t i = 0; i < 3; ++i) {
    const Vector2 b{bases[i][0] + l * std::cos(theta[i]), bases[i][1] + l * std::sin(theta[i])};
    const double error = std::abs((c - b).norm() - l) / l;
    // Not (error <= ...) so that NaN counts as the worst mismatch.
    if (!(error <= out.length_error)) out.length_error = std::isnan(error) ? INFINITY : error;
    const Vector2 to_centre = c - bases[i], to_elbow = b - bases[i];
    const double cross = to_centre[0] * to_elbow[1] - to_centre[1] * to_elbow[0];
    if (out.wrong_elbow == 0 && p.elbow[i] * cross < -kClosureTolerance * to_centre.norm() * l) {
      out.wrong_elbow = static_cast<int>(i) + 1;
    }
  }
  return out;
}

Matrix23 CalcTransposedInverseJacobian(const PlanarRobotParameters& p, const Vector2& c, const Vector3& theta) {
  const auto bases = CalcBaseJoints(p.base_distance);
  Matrix23 g = Matrix23::Zero();
  for (std::size_t i = 0; i < 3; ++i) {
    const double ct = std::cos(theta[i]), st = std::sin(theta[i]);
    const double dx = c[0] - bases[i][0] - p.link_length * ct, dy = c[1] - bases[i][1] - p.link_length * st;
    const double s = p.link_length * (-dx * st + dy * ct);  // l d . e_perp
    g(0, i) = dx / s;
    g(1, i) = dy / s;
  }
  return g;
}

Matrix23 CalcTransposedInverseJacobianRate(const PlanarRobotParameters& p, const Vector2& c, const Vector3& theta,
                                           const Vector2& v) {
  const auto bases = CalcBaseJoints(p.base_distance);
  const Matrix23 g = CalcTransposedInverseJacobian(p, c, theta);
  Matrix23 rate = Matrix23::Zero();
  const double l = p.link_length;
  for (std::size_t i = 0; i < 3; ++i) {
    const double ct = std::cos(theta[i]), st = std::sin(theta[i]);
    const double dx = c[0] - bases[i][0] - l * ct, dy = c[1] - bases[i][1] - l * st;
    const double theta_rate = g(0, i) * v[0] + g(1, i) * v[1];
    // d' = x' - l e_perp theta', e_perp' = -e theta', s = l d . e_perp.
    const double ddx = v[0] + l * st * theta_rate, ddy = v[1] - l * ct * theta_rate;
    const double s = l * (-dx * st + dy * ct);
    const double s_rate = l * ((-ddx * st + ddy * ct) - (dx * ct + dy * st) * theta_rate);
    rate(0, i) = ddx / s - dx * s_rate / (s * s);
    rate(1, i) = ddy / s - dy * s_rate / (s * s);
  }
  return rate;
}

Vector3 CalcNullSpace(const Matrix23& g) {
  Vector3 n = {g(0, 1) * g(1, 2) - g(0, 2) * g(1, 1), g(0, 2) * g(1, 0) - g(0, 0) * g(1, 2), g(0, 0) * g(1, 1) - g(0, 1) * g(1, 0)};
  const double norm = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const double sign = n[0] >= 0.0 ? 1.0 : -1.0;
  for (double& v : n) v *= sign / norm;
  return n;
}

Vector3 ApplyPseudoInverse(const Matrix23& g, const Vector2& f) {
  const double a = g(0, 0) * g(0, 0) + g(0, 1) * g(0, 1) + g(0, 2) * g(0, 2);
  const double b = g(0, 0) * g(1, 0) + g(0, 1) * g(1, 1) + g(0, 2) * g(1, 2);
  const double d = g(1, 0) * g(1, 0) + g(1, 1) * g(1, 1) + g(1, 2) * g(1, 2);
  const double det = a * d - b * b;
  const double y0 = (d * f[0] - b * f[1]) / det, y1 = (a * f[1] - b * f[0]) / det;  // (G G')^-1 f
  return {g(0, 0) * y0 + g(1, 0) * y1, g(0, 1) * y0 + g(1, 1) * y1, g(0, 2) * y0 + g(1, 2) * y1};
}

namespace {
// G G', symmetric to the last bit (a general product need not be).
Matrix2 CalcGramian(const Matrix23& g) {
  Matrix2 gramian = g * g.transpose();
  gramian(1, 0) = gramian(0, 1);
  return gramian;
}
}  // namespace

Matrix2 CalcCartesianMass(const PlanarRobotParameters& p, const Matrix23& g) {
  return p.output_inertia * CalcGramian(g) + p.center_mass * Matrix2::Identity();
}

Matrix2 CalcCartesianDamping(const PlanarRobotParameters& p, const Matrix23& g, const Matrix23& r) {
  const double friction = p.gear_ratio * p.gear_ratio * p.viscous_friction;
  return p.output_inertia * g * r.transpose() + friction * CalcGramian(g);
}

}  // namespace driveid
