#include "report/planar_robot_report.h"

#include <fmt/format.h>

namespace driveid {

PlanarRobotReport CalcPlanarRobotReport(const PlanarRobotParameters& r, const Vector2& pose, const Vector2& velocity,
                                        const std::string& source) {
  PlanarRobotReport q;
  q.source = source;
  q.robot = r;
  q.pose = pose;
  q.velocity = velocity;
  q.theta = CalcInverseKinematics(r, pose);
  q.g = CalcTransposedInverseJacobian(r, pose, q.theta);
  q.m = CalcCartesianMass(r, q.g);
  q.c = CalcCartesianDamping(r, q.g, CalcTransposedInverseJacobianRate(r, pose, q.theta, velocity));
  q.n = CalcNullSpace(q.g);
  return q;
}

std::string FormatPlanarRobotReport(const PlanarRobotReport& q) {
  const PlanarRobotParameters& r = q.robot;
  const Vector2& pose = q.pose;
  const Vector2& velocity = q.velocity;
  const std::string& source = q.source;
  const Vector3& theta = q.theta;
  const Matrix23& g = q.g;
  const Matrix2& m = q.m;
  const Matrix2& c = q.c;
  const Vector3& n = q.n;
  std::string out = fmt::format("planar robot from {} (seed 000 sections 2, 5; docs/models.md#planar-robot)\n", source);
  out += fmt::format("  Theta = {} kg m^2 (seed: 0.55), m_c = {} kg (0.5), d_g = {} N m s/rad (0.002), n_g = {}, k_t = {} N m/A\n",
                     r.output_inertia, r.center_mass, r.viscous_friction, r.gear_ratio, r.torque_constant);
  out += fmt::format("pose C = ({:.4f}, {:.4f}) m, velocity ({:.3f}, {:.3f}) m/s; joint angles ({:.4f}, {:.4f}, {:.4f}) rad\n",
                     pose[0], pose[1], velocity[0], velocity[1], theta[0], theta[1], theta[2]);
  out += fmt::format("  G  = [[{:.5g}, {:.5g}, {:.5g}], [{:.5g}, {:.5g}, {:.5g}]] 1/m\n", g(0, 0), g(0, 1), g(0, 2), g(1, 0), g(1, 1), g(1, 2));
  out += fmt::format("  null space of G (internal prestress): ({:.4f}, {:.4f}, {:.4f})\n", n[0], n[1], n[2]);
  out += fmt::format("  M = Theta G G' + m_c 1          = [[{:.5g}, {:.5g}], [{:.5g}, {:.5g}]] kg\n", m(0, 0), m(0, 1), m(1, 0), m(1, 1));
  out += fmt::format("  C = Theta G dG' + n_g^2 d_g G G' = [[{:.5g}, {:.5g}], [{:.5g}, {:.5g}]] N s/m\n", c(0, 0), c(0, 1), c(1, 0),
                     c(1, 1));
  out += "  (the seed prints G G^-1 in eq. (22) and a garbled eq. (23); docs/models.md gives the forms above)\n";
  return out;
}

Json PlanarRobotReportJson(const PlanarRobotReport& q) {
  const PlanarRobotParameters& r = q.robot;
  const Vector2& pose = q.pose;
  const Vector2& velocity = q.velocity;
  const std::string& source = q.source;
  const Vector3& theta = q.theta;
  const Matrix23& g = q.g;
  const Matrix2& m = q.m;
  const Matrix2& c = q.c;
  const Vector3& n = q.n;
  Json out;
  out["source"] = source;
  out["parameters"] = Json::object();
  for (const auto& row : PlanarRobotParameterTable()) out["parameters"][row.spec.key] = r.*(row.in_model);
  out["pose"] = {pose[0], pose[1]};
  out["velocity"] = {velocity[0], velocity[1]};
  out["joint_angles"] = {theta[0], theta[1], theta[2]};
  out["G"] = {{g(0, 0), g(0, 1), g(0, 2)}, {g(1, 0), g(1, 1), g(1, 2)}};
  out["null_space"] = {n[0], n[1], n[2]};
  out["M"] = {{m(0, 0), m(0, 1)}, {m(1, 0), m(1, 1)}};
  out["C"] = {{c(0, 0), c(0, 1)}, {c(1, 0), c(1, 1)}};
  return out;
}

}  // namespace driveid
