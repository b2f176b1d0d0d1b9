// The redundantly actuated planar parallel robot of seed 000 (sections 2, 5;
// docs/models.md#planar-robot). Base joints A1 = (0, 0), A2 = (a, 0), A3 = (a/2, a sqrt(3)/2);
// legs A_i - B_i - C with links of length l; joint angle theta_i is the angle
// of A_i B_i from +x, counter-clockwise, at the gear output. elbow_i = +1
// puts B_i counter-clockwise of the ray A_i -> C:
//   theta_i = atan2(C - A_i) + elbow_i acos(|C - A_i| / (2 l)).
// Velocities: theta' = G' x' with G (2 x 3) the transposed inverse Jacobian,
//   column i: g_i = d_i / (l d_i . e_perp(theta_i)),  d_i = C - B_i,
//   e(theta) = (cos, sin), e_perp(theta) = (-sin, cos).
// (From |C - B_i| = l: d_i . (x' - l e_perp theta_i') = 0.) Static force f = G tau.
// Rigid-body model (all masses lumped into the actuators and the centre joint):
//   Theta theta'' + n_g^2 d_g theta' + G+ (m_c x'' + f_ext) = n_g tau_motor,m,  G+ = G'(G G')^-1
// and, multiplied by G, M x'' + C x' = n_g G tau_motor - f_ext with
//   M = Theta G G' + m_c 1,  C = Theta G dG' + n_g^2 d_g G G'
// (the seed prints G G^-1 in (22) and a garbled (23)). The null-space part of
// tau_motor (internal prestress, G tau = 0) produces no motion.
#pragma once

#include <array>
#include <optional>

#include "models/cdrive.h"  // Vector2
#include "models/parameter_table.h"

namespace driveid {

struct PlanarRobotParameters {
  double base_distance = 1.0;   ///< a [m]
  double link_length = 0.488;   ///< l [m]
  std::array<int, 3> elbow = {1, 1, 1};
  double gear_ratio = 80.0;     ///< n_g [-]
  double output_inertia = 0.55; ///< Theta = n_g^2 (Theta_motor + Theta_g) + m_B l^2 [kg m^2]
  double center_mass = 0.5;     ///< m_c [kg]
  double viscous_friction = 0.002;  ///< d_g, at the gear input [N m s/rad]
  double torque_constant = 0.5;     ///< k_t [N m/A]
};

/// The parameter file's `planar_robot` section as written.
struct PlanarRobotSection {
  static constexpr const char* kSectionName = "planar_robot";
  std::optional<double> base_distance, link_length, gear_ratio, output_inertia, center_mass, viscous_friction,
      torque_constant;
  std::optional<std::array<int, 3>> elbow;  ///< +1: B_i counter-clockwise of the ray A_i -> C
};

/// The robot's parameters; the robot fit estimates Theta, m_c, d_g.
inline const ParameterTable<PlanarRobotSection, PlanarRobotParameters>& PlanarRobotParameterTable() {
  using S = PlanarRobotSection;
  using P = PlanarRobotParameters;
  static const ParameterTable<S, P> table = {
      {Spec("base_distance", "a", "m", "distance of the base joints").Above(0.0).Required(),
       &S::base_distance, &P::base_distance},
      {Spec("l", "l", "m", "link length").Above(0.0).Required(), &S::link_length, &P::link_length},
      {Spec("n_g", "n_g", "-", "gear ratio").Above(0.0).Required(), &S::gear_ratio, &P::gear_ratio},
      {Spec("Theta", "Theta", "kg m^2", "actuator inertia at the gear output").Required().Fit("robot").FreeByDefault(),
       &S::output_inertia, &P::output_inertia},
      {Spec("m_c", "m_c", "kg", "mass of the centre joint").Required().Fit("robot").FreeByDefault(), &S::center_mass,
       &P::center_mass},
      {Spec("d_g", "d_g", "N m s/rad", "gearbox viscous friction at the gear input").Required().Fit("robot")
           .FreeByDefault(),
       &S::viscous_friction, &P::viscous_friction},
      {Spec("k_t", "k_t", "N m/A", "motor torque constant").Above(0.0).Required(), &S::torque_constant,
       &P::torque_constant},
  };
  return table;
}

/// The parameters of a section (elbows +1 when not given); throws
/// InputError naming a missing or out-of-range value.
inline PlanarRobotParameters MakePlanarRobotParameters(const PlanarRobotSection& section) {
  PlanarRobotParameters p = MakeModelParameters(PlanarRobotParameterTable(), section, PlanarRobotParameters{},
                                                "planar_robot");
  p.elbow = section.elbow.value_or(std::array<int, 3>{1, 1, 1});
  return p;
}

using Matrix23 = Eigen::Matrix<double, 2, 3>;  ///< G
using Vector3 = Eigen::Vector3d;

std::array<Vector2, 3> CalcBaseJoints(double base_distance);

/// Joint angles for the centre joint at `c`; throws std::domain_error if a
/// leg cannot reach it (|C - A_i| > 2 l).
Vector3 CalcInverseKinematics(const PlanarRobotParameters& p, const Vector2& c);

/// Centre joint from joint angles: least-squares intersection of the three
/// circles |C - B_i| = l by Gauss-Newton from `guess`.
Vector2 CalcForwardKinematics(const PlanarRobotParameters& p, const Vector3& theta, const Vector2& guess);

/// How far joint angles are from an assembled robot, for the centre joint `c`
/// from CalcForwardKinematics: the largest leg-length mismatch
/// max_i | |C - B_i| - l | / l, and whether every elbow is on its side
/// (elbow_i (C - A_i) x (B_i - A_i) >= -kClosureTolerance |C - A_i| l).
struct ClosureCheck {
  double length_error = 0.0;  ///< relative to l [-]
  int wrong_elbow = 0;        ///< 1-based leg whose elbow is on the other side, 0 if none
};
/// Largest accepted relative mismatch (1 % of l; docs/models.md#planar-robot).
inline constexpr double kClosureTolerance = 0.01;
ClosureCheck CalcClosure(const PlanarRobotParameters& p, const Vector3& theta, const Vector2& c);

/// G at a pose (c with its joint angles theta).
Matrix23 CalcTransposedInverseJacobian(const PlanarRobotParameters& p, const Vector2& c, const Vector3& theta);
/// dG/dt at a pose moving with x' (theta' = G' x').
Matrix23 CalcTransposedInverseJacobianRate(const PlanarRobotParameters& p, const Vector2& c, const Vector3& theta,
                                           const Vector2& velocity);

/// Unit vector spanning the null space of G (G n = 0), first component >= 0.
Vector3 CalcNullSpace(const Matrix23& g);
/// G+ = G'(G G')^-1 applied to a Cartesian force.
Vector3 ApplyPseudoInverse(const Matrix23& g, const Vector2& force);

/// Cartesian mass matrix M = Theta G G' + m_c 1 (row-major 2 x 2) and
/// C = Theta G dG' + n_g^2 d_g G G'.
Matrix2 CalcCartesianMass(const PlanarRobotParameters& p, const Matrix23& g);
Matrix2 CalcCartesianDamping(const PlanarRobotParameters& p, const Matrix23& g, const Matrix23& g_rate);

}  // namespace driveid
