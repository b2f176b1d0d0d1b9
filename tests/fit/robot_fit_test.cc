// Robot rigid-body identification (docs/models.md#planar-robot): recovery from the triangle with
// prestress, encoder quantisation and current noise; the prestress has no
// influence; the current prediction matches the motion part of the current.
#include "fit/robot/robot_fit.h"
#include "sim/robot_experiment.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "support/reference_robot.h"

using namespace driveid;

namespace {
PlanarRobotParameters Start() {
  PlanarRobotParameters p;
  p.output_inertia = 1.0;
  p.center_mass = 1.0;
  p.viscous_friction = 0.001;
  return p;
}
}  // namespace

TEST_CASE("robot: Theta within 3 %, d_g within 5 %, m_c within 15 % from the noisy triangle") {
  const PlanarRobotParameters truth;
  for (std::uint64_t seed : {1u, 2u, 3u, 4u}) {
    RobotExperiment e;
    e.current_noise = 0.02;
    e.prestress = 3.0;
    e.seed = seed;
    const RobotFitOutput out = FitRobot({SimulateRobotExperiment(truth, e)}, Start(), {});
    INFO("seed " << seed << ": Theta " << out.params.output_inertia << ", m_c " << out.params.center_mass << ", d_g "
                 << out.params.viscous_friction);
    CHECK(out.params.output_inertia == Approx(truth.output_inertia).epsilon(0.03));
    CHECK(out.params.viscous_friction == Approx(truth.viscous_friction).epsilon(0.05));
    CHECK(out.params.center_mass == Approx(truth.center_mass).epsilon(0.15));
  }
}

TEST_CASE("robot: the null-space prestress drops out, and the prediction matches the motion current") {
  const PlanarRobotParameters truth;
  RobotExperiment with, without;
  with.prestress = 3.0;
  without.prestress = 0.0;
  const auto a = FitRobot({SimulateRobotExperiment(truth, with)}, Start(), {});
  const auto b = FitRobot({SimulateRobotExperiment(truth, without)}, Start(), {});
  // A 3 N m prestress moves nothing: only through G evaluated at the
  // quantised, smoothed pose (G n is zero only at the exact pose).
  CHECK(a.params.output_inertia == Approx(b.params.output_inertia).epsilon(1e-5));
  CHECK(a.params.center_mass == Approx(b.params.center_mass).epsilon(1e-5));
  // Away from the trapezoid's acceleration jumps the model current equals
  // the minimum-norm part of the measured one.
  const auto& p = a.predictions.front();
  int close = 0;
  for (std::size_t k = 0; k < p.time.size(); ++k) close += std::abs(p.total[0][k] - p.measured_motion[0][k]) < 0.05;
  INFO(close << " of " << p.time.size() << " samples within 0.05 A");
  // Each of the 36 acceleration jumps spoils about +-5 ms of the smoothed derivatives.
  CHECK(close > static_cast<int>(0.75 * static_cast<double>(p.time.size())));
  // The split adds up.
  CHECK(p.inertia[1][100] + p.coriolis[1][100] + p.friction[1][100] == Approx(p.total[1][100]));
}

TEST_CASE("robot: logs of the independent generator (own IK, numerical Jacobian) give the same recovery") {
  for (unsigned seed : {7u, 8u}) {
    const auto ref = reference::SimulateTriangle(reference::Robot{}, 3, 0.05, 3.0, 0.02, seed);
    RobotLog log;
    log.path = "reference";
    log.time = ref.t;
    log.angle = ref.theta;
    log.current = ref.current;
    const RobotFitOutput out = FitRobot({log}, Start(), {});
    INFO("seed " << seed << ": Theta " << out.params.output_inertia << ", m_c " << out.params.center_mass << ", d_g "
                 << out.params.viscous_friction);
    CHECK(out.params.output_inertia == Approx(0.55).epsilon(0.03));
    CHECK(out.params.viscous_friction == Approx(0.002).epsilon(0.05));
    CHECK(out.params.center_mass == Approx(0.5).epsilon(0.15));
  }
}
