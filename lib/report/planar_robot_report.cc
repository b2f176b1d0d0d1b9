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
  std::string out = fmt::format("planar robot from {} (seed 000 sections 2, 5; docs/models.md#planar-robot)\n", q.source);
  out += fmt::format("  Theta = {} kg m^2 (seed: 0.55), m_c = {} kg (0.5), d_g = {} N m s/rad (0.002), n_g = {}, k_t = {} N m/A\n",
                     q.robot.output_inertia, q.robot.center_mass, q.robot.viscous_friction, q.robot.gear_ratio, q.robot.torque_constant);
  out += fmt::format("pose C = ({:.4f}, {:.4f}) m, velocity ({:.3f}, {:.3f}) m/s; joint angles ({:.4f}, {:.4f}, {:.4f}) rad\n",
                     q.pose[0], q.pose[1], q.velocity[0], q.velocity[1], q.theta[0], q.theta[1], q.theta[2]);
  out += fmt::format("  G  = [[{:.5g}, {:.5g}, {:.5g}], [{:.5g}, {:.5g}, {:.5g}]] 1/m\n", q.g(0, 0), q.g(0, 1), q.g(0, 2), q.g(1, 0), q.g(1, 1), q.g(1, 2));
  out += fmt::format("  null space of G (internal prestress): ({:.4f}, {:.4f}, {:.4f})\n", q.n[0], q.n[1], q.n[2]);
  out += fmt::format("  M = Theta G G' + m_c 1          = [[{:.5g}, {:.5g}], [{:.5g}, {:.5g}]] kg\n", q.m(0, 0), q.m(0, 1), q.m(1, 0), q.m(1, 1));
  out += fmt::format("  C = Theta G dG' + n_g^2 d_g G G' = [[{:.5g}, {:.5g}], [{:.5g}, {:.5g}]] N s/m\n", q.c(0, 0), q.c(0, 1), q.c(1, 0),
                     q.c(1, 1));
  out += "  (the seed prints G G^-1 in eq. (22) and a garbled eq. (23); docs/models.md gives the forms above)\n";
  return out;
}

Json PlanarRobotReportJson(const PlanarRobotReport& q) {
  Json out;
  out["source"] = q.source;
  out["parameters"] = Json::object();
  for (const auto& row : PlanarRobotParameterTable()) out["parameters"][row.spec.key] = q.robot.*(row.in_model);
  out["pose"] = {q.pose[0], q.pose[1]};
  out["velocity"] = {q.velocity[0], q.velocity[1]};
  out["joint_angles"] = {q.theta[0], q.theta[1], q.theta[2]};
  out["G"] = {{q.g(0, 0), q.g(0, 1), q.g(0, 2)}, {q.g(1, 0), q.g(1, 1), q.g(1, 2)}};
  out["null_space"] = {q.n[0], q.n[1], q.n[2]};
  out["M"] = {{q.m(0, 0), q.m(0, 1)}, {q.m(1, 0), q.m(1, 1)}};
  out["C"] = {{q.c(0, 0), q.c(0, 1)}, {q.c(1, 0), q.c(1, 1)}};
  return out;
}

}  // namespace driveid
