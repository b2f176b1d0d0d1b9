#include "support/reference_robot.h"

#include <cmath>
#include <random>

namespace reference {
namespace {

struct Point {
  double x, y;
};

std::array<double, 3> InverseKinematics(const Robot& r, Point c) {
  const Point bases[3] = {{0, 0}, {r.a, 0}, {r.a / 2, r.a * std::sqrt(3.0) / 2}};
  std::array<double, 3> theta{};
  for (int i = 0; i < 3; ++i) {
    const double dx = c.x - bases[i].x, dy = c.y - bases[i].y;
    theta[static_cast<std::size_t>(i)] = std::atan2(dy, dx) + std::acos(std::hypot(dx, dy) / (2 * r.l));
  }
  return theta;
}

// Position along the triangle at time t: rest-to-rest trapezoids with a dwell first.
Point Path(const Robot& r, double t, int loops, double dwell) {
  const double side = 0.25, acc = 50.0, v = 3.0;
  const Point centre = {r.a / 2, r.a / (2 * std::sqrt(3.0))};
  Point corner[3];
  for (int k = 0; k < 3; ++k) {
    const double angle = M_PI / 2 + k * 2 * M_PI / 3;
    corner[k] = {centre.x + side / std::sqrt(3.0) * std::cos(angle), centre.y + side / std::sqrt(3.0) * std::sin(angle)};
  }
  const double ta = v / acc, tc = (side - v * v / acc) / v, move = 2 * ta + tc, edge_time = dwell + move;
  int edge = static_cast<int>(t / edge_time);
  double u = t - edge * edge_time - dwell;
  if (edge >= 3 * loops) {
    edge = 3 * loops - 1;
    u = move;
  }
  double s;
  if (u <= 0) s = 0;
  else if (u < ta) s = 0.5 * acc * u * u;
  else if (u < ta + tc) s = 0.5 * acc * ta * ta + v * (u - ta);
  else if (u < move) s = side - 0.5 * acc * (move - u) * (move - u);
  else s = side;
  const Point from = corner[edge % 3], to = corner[(edge + 1) % 3];
  return {from.x + s / side * (to.x - from.x), from.y + s / side * (to.y - from.y)};
}

}  // namespace

RobotLog SimulateTriangle(const Robot& r, int loops, double dwell, double prestress, double noise, unsigned seed) {
  std::mt19937 engine(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  const double quantum = 2 * M_PI / (8192 * r.n_g);
  const double ta = 0.06, tc = (0.25 - 0.18) / 3.0, duration = loops * 3 * (dwell + 2 * ta + tc) + dwell;
  const double h = 1e-5;  // step of the numerical derivatives [s] and [m]
  RobotLog log;
  for (long k = 0; k <= std::lround(duration * 1000); ++k) {
    const double t = static_cast<double>(k) / 1000.0;
    const Point c = Path(r, t, loops, dwell), cp = Path(r, t + h, loops, dwell), cm = Path(r, t - h, loops, dwell);
    const auto th = InverseKinematics(r, c), thp = InverseKinematics(r, cp), thm = InverseKinematics(r, cm);
    const double ax = (cp.x - 2 * c.x + cm.x) / (h * h), ay = (cp.y - 2 * c.y + cm.y) / (h * h);
    // G' = dtheta/dx by central differences in x and y.
    const auto tx1 = InverseKinematics(r, {c.x + h, c.y}), tx0 = InverseKinematics(r, {c.x - h, c.y});
    const auto ty1 = InverseKinematics(r, {c.x, c.y + h}), ty0 = InverseKinematics(r, {c.x, c.y - h});
    double g[2][3];
    for (int i = 0; i < 3; ++i) {
      g[0][i] = (tx1[static_cast<std::size_t>(i)] - tx0[static_cast<std::size_t>(i)]) / (2 * h);
      g[1][i] = (ty1[static_cast<std::size_t>(i)] - ty0[static_cast<std::size_t>(i)]) / (2 * h);
    }
    // G+ f = G' (G G')^-1 f for f = m_c x''; null space n = row0 x row1.
    const double s00 = g[0][0] * g[0][0] + g[0][1] * g[0][1] + g[0][2] * g[0][2];
    const double s01 = g[0][0] * g[1][0] + g[0][1] * g[1][1] + g[0][2] * g[1][2];
    const double s11 = g[1][0] * g[1][0] + g[1][1] * g[1][1] + g[1][2] * g[1][2];
    const double det = s00 * s11 - s01 * s01;
    const double fx = r.m_c * ax, fy = r.m_c * ay;
    const double y0 = (s11 * fx - s01 * fy) / det, y1 = (s00 * fy - s01 * fx) / det;
    double n[3] = {g[0][1] * g[1][2] - g[0][2] * g[1][1], g[0][2] * g[1][0] - g[0][0] * g[1][2],
                   g[0][0] * g[1][1] - g[0][1] * g[1][0]};
    const double norm = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    log.t.push_back(t);
    for (int i = 0; i < 3; ++i) {
      const std::size_t j = static_cast<std::size_t>(i);
      const double rate = (thp[j] - thm[j]) / (2 * h);
      const double acceleration = (thp[j] - 2 * th[j] + thm[j]) / (h * h);
      const double torque = r.Theta * acceleration + r.n_g * r.n_g * r.d_g * rate + g[0][i] * y0 + g[1][i] * y1 +
                            prestress * n[i] / norm;
      log.theta[j].push_back(std::floor(th[j] / quantum) * quantum);
      log.current[j].push_back(torque / (r.n_g * r.k_t) + gauss(engine));
    }
  }
  return log;
}

}  // namespace reference
