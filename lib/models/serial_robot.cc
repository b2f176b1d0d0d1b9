#include "models/serial_robot.h"

#include <Eigen/Geometry>

namespace driveid {

RigidTransform Compose(const RigidTransform& a, const RigidTransform& b) {
  return {a.rotation * b.rotation, a.rotation * b.translation + a.translation};
}

Eigen::Matrix3d RotationFromRpy(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

const std::array<const char*, kInertialParameters>& InertialParameterNames() {
  static const std::array<const char*, kInertialParameters> names = {"m",   "mx",  "my",  "mz",  "Ixx",
                                                                     "Ixy", "Ixz", "Iyy", "Iyz", "Izz"};
  return names;
}

namespace {

InertialParameters Pack(double m, const Eigen::Vector3d& h, const Eigen::Matrix3d& i) {
  return {m, h.x(), h.y(), h.z(), i(0, 0), i(0, 1), i(0, 2), i(1, 1), i(1, 2), i(2, 2)};
}

// |x|^2 1 - x x^T: the inertia of a unit point mass at x about the origin.
Eigen::Matrix3d PointInertia(const Eigen::Vector3d& x) {
  return x.squaredNorm() * Eigen::Matrix3d::Identity() - x * x.transpose();
}

}  // namespace

InertialParameters InertialFromCentre(double mass, const Eigen::Vector3d& centre, const Eigen::Matrix3d& inertia_at_centre) {
  // Parallel axis theorem, from the centre of mass to the frame's origin.
  return Pack(mass, mass * centre, inertia_at_centre + mass * PointInertia(centre));
}

Eigen::Matrix3d InertiaMatrix(const InertialParameters& pi) {
  Eigen::Matrix3d i;
  i << pi[4], pi[5], pi[6], pi[5], pi[7], pi[8], pi[6], pi[8], pi[9];
  return i;
}

InertialParameters TransformInertial(const InertialParameters& pi, const RigidTransform& t) {
  // A point x_old of the body lies at x = R x_old + p. Integrating
  // |x|^2 1 - x x^T over the mass term by term gives, with h' = R h,
  //   I_new = R I R^T + 2 (p . h') 1 - (h' p^T + p h'^T) + m (|p|^2 1 - p p^T),
  // and h_new = h' + m p: no division by the mass (a massless body stays 0).
  const double m = pi[0];
  const Eigen::Vector3d h = t.rotation * Eigen::Vector3d(pi[1], pi[2], pi[3]);
  const Eigen::Vector3d& p = t.translation;
  const Eigen::Matrix3d i = t.rotation * InertiaMatrix(pi) * t.rotation.transpose() +
                            2.0 * p.dot(h) * Eigen::Matrix3d::Identity() - (h * p.transpose() + p * h.transpose()) +
                            m * PointInertia(p);
  return Pack(m, h + m * p, i);
}

}  // namespace driveid
