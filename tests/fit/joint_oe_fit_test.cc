// Output-error joint (docs/models.md#joint-output-error): the simulator's
// sensitivities against finite differences through stick-slip events,
// recovery of a closed-loop joint with sticking motor friction from the
// test's own generator (tests/support/reference_joint_friction.h), refusals.
#include "fit/joint_oe_fit.h"

#include <array>
#include <cmath>
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "fit/joint_fit.h"
#include "sim/joint_simulator.h"
#include "support/reference_joint_friction.h"

using namespace driveid;
using driveid::testing::FrictionJointExperiment;
using driveid::testing::FrictionJointTruth;

namespace {

JointLog ToLog(const driveid::testing::FrictionJointLog& g, const std::string& path) {
  JointLog log;
  log.path = path;
  log.time = g.t;
  log.motor_position = g.q_motor;
  log.link_position = g.q_link;
  log.torque = g.tau;
  return log;
}

JointSection StartSection(const FrictionJointTruth& t) {
  JointSection s;
  s.gear_ratio = t.gear_ratio;
  s.motor_inertia = 1.3 * t.motor_inertia;
  s.link_inertia = 0.8 * t.link_inertia;
  s.stiffness = 1.4 * t.stiffness;
  s.damping = 1.0;
  s.motor_viscous = 1.0;
  s.motor_coulomb = 1.0;
  s.link_viscous = 0.0;
  s.link_coulomb = 0.0;
  s.offset = 0.0;
  return s;
}

}  // namespace

TEST_CASE("joint OE recovers a closed-loop joint with sticking motor friction", "[joint-oe]") {
  const FrictionJointTruth truth;
  FrictionJointExperiment experiment;
  experiment.seed = 3;
  const auto generated = driveid::testing::SimulateFrictionJoint(truth, experiment);
  INFO("sticks " << generated.sticks);
  CHECK(generated.sticks >= 4);
  const std::vector<JointLog> logs = {ToLog(generated, "closed_loop.csv")};
  const JointSection start = StartSection(truth);
  JointFitOptions id_options;
  id_options.per_log = id_options.sensitivity = false;
  id_options.refuse_undetermined = false;
  const JointFitOutput id = FitJoint(logs, start, id_options);
  const JointOeOutput oe = FitJointOutputError(logs, start, &id.params, {});
  const auto check = [&](const char* name, double value, double tolerance) {
    for (const auto& e : oe.fit.estimates) {
      if (e.name != name) continue;
      double id_value = 0.0;
      for (const auto& i : id.fit.estimates) id_value = i.name == name ? i.value : id_value;
      INFO(name << " = " << e.value << " +- " << e.standard_error << ", truth " << value << " (inverse dynamics "
                << id_value << ")");
      CHECK(std::abs(e.value - value) <= tolerance * value);
      CHECK(e.ci95_low <= value);
      CHECK(value <= e.ci95_high);
      return;
    }
    FAIL("no estimate " << name);
  };
  check("motor_inertia", truth.motor_inertia, 0.02);
  check("link_inertia", truth.link_inertia, 0.02);
  check("stiffness", truth.stiffness, 0.02);
  check("damping", truth.damping, 0.10);
  check("motor_viscous", truth.motor_viscous, 0.10);
  check("motor_coulomb", truth.motor_coulomb, 0.10);
}

namespace {
JointParameters TruthParameters(const FrictionJointTruth& truth) {
  JointParameters p;
  p.motor_inertia = truth.motor_inertia;
  p.link_inertia = truth.link_inertia;
  p.stiffness = truth.stiffness;
  p.damping = truth.damping;
  p.motor_viscous = truth.motor_viscous;
  p.motor_coulomb = truth.motor_coulomb;
  p.link_viscous = truth.link_viscous;
  p.offset = truth.offset;
  return p;
}
const std::vector<int> kTerms = {kJointMotorInertia, kJointLinkInertia, kJointStiffness, kJointDamping,
                                 kJointMotorViscous, kJointMotorCoulomb, kJointLinkViscous, kJointOffset};
}  // namespace

TEST_CASE("joint simulator: the exact path reproduces the independent generator", "[joint-oe]") {
  // Noise-free, unquantised: the generator's RK4 (200 sub-steps, stops located
  // by interpolation) against the simulator's matrix exponentials.
  const FrictionJointTruth truth;
  FrictionJointExperiment experiment;
  experiment.noise = 0.0;
  experiment.motor_counts = experiment.link_counts = 1e15;
  experiment.substeps = 200;
  const auto g = driveid::testing::SimulateFrictionJoint(truth, experiment);
  REQUIRE(g.sticks >= 10);
  std::vector<double> u;
  for (double t : g.tau) u.push_back(truth.gear_ratio * t);
  JointSimulator exact(kTerms, 1e-12, 1e-9);
  JointStateResponse a;
  exact.Simulate(TruthParameters(truth), g.t, u, {0, 0, 0, 0}, false, &a);
  double motor = 0.0, link = 0.0;
  for (std::size_t k = 0; k < g.t.size(); ++k) {
    motor = std::max(motor, std::abs(a.state[4 * k] - g.q_motor[k] / truth.gear_ratio));
    link = std::max(link, std::abs(a.state[4 * k + 2] - g.q_link[k]));
  }
  INFO("worst motor " << motor << " rad, link " << link << " rad");
  CHECK(motor < 1e-8);
  CHECK(link < 1e-8);
}

TEST_CASE("joint simulator: exact path, integrator and finite differences agree through stick-slip", "[joint-oe]") {
  const FrictionJointTruth truth;
  FrictionJointExperiment experiment;
  experiment.duration = 3.0;
  const auto g = driveid::testing::SimulateFrictionJoint(truth, experiment);
  const JointParameters p = TruthParameters(truth);
  std::vector<double> u;
  for (double t : g.tau) u.push_back(truth.gear_ratio * t);
  // A moving start, so that every initial state matters (a stuck motor's start rate does not).
  const std::array<double, 4> x0 = {0.01, 0.5, 0.0, 0.2};
  std::vector<int> terms = kTerms;
  for (int t : {kJointInitialMotorAngle, kJointInitialMotorRate, kJointInitialLinkAngle, kJointInitialLinkRate}) {
    terms.push_back(t);
  }
  JointSimulator exact(terms, 1e-12, 1e-9), integrated(terms, 1e-12, 1e-9);
  integrated.set_use_integrator(true);
  JointStateResponse a, b;
  exact.Simulate(p, g.t, u, x0, true, &a);
  integrated.Simulate(p, g.t, u, x0, true, &b);
  REQUIRE(a.switch_count >= 4);
  CHECK(a.switch_count == b.switch_count);
  // States: the integrator agrees to 1e-3 of the deflection's scale (its tolerances).
  double worst = 0.0, deflection = 0.0;
  for (std::size_t i = 0; i < a.state.size(); ++i) worst = std::max(worst, std::abs(a.state[i] - b.state[i]));
  for (std::size_t k = 0; k < g.t.size(); ++k) {
    deflection = std::max(deflection, std::abs(a.state[4 * k] - a.state[4 * k + 2]));
  }
  INFO("deflection up to " << deflection << " rad");
  CHECK(worst < 1e-3 * deflection);
  // Sensitivities of the link angle: exact path vs integrator vs central differences.
  const std::size_t np = terms.size(), samples = g.t.size();
  for (std::size_t j = 0; j < np; ++j) {
    JointParameters up = p, down = p;
    std::array<double, 4> x_up = x0, x_down = x0;
    const int state = InitialStateIndex(terms[j]);
    double h = 1e-6;
    if (state < 0) {
      const double value = p.*(JointParameterTable()[terms[j]].in_model);
      h = 1e-5 * std::max(std::abs(value), 1e-3);
      up.*(JointParameterTable()[terms[j]].in_model) += h;
      down.*(JointParameterTable()[terms[j]].in_model) -= h;
    } else {
      x_up[static_cast<std::size_t>(state)] += h;
      x_down[static_cast<std::size_t>(state)] -= h;
    }
    JointStateResponse ru, rd;
    exact.Simulate(up, g.t, u, x_up, false, &ru);
    exact.Simulate(down, g.t, u, x_down, false, &rd);
    double scale = 0.0, error_fd = 0.0, error_integrator = 0.0;
    for (std::size_t k = 0; k < samples; ++k) {
      for (int i : {0, 2}) {
        const double s = a.sensitivity[(k * np + j) * 4 + i];
        const double fd = (ru.state[4 * k + i] - rd.state[4 * k + i]) / (2.0 * h);
        scale = std::max(scale, std::abs(s));
        error_fd = std::max(error_fd, std::abs(s - fd));
        error_integrator = std::max(error_integrator, std::abs(s - b.sensitivity[(k * np + j) * 4 + i]));
      }
    }
    INFO("term " << terms[j] << ": scale " << scale << ", fd error " << error_fd
                 << ", integrator error " << error_integrator);
    CHECK(error_fd < 1e-3 * scale);
    CHECK(error_integrator < 1e-3 * scale);
  }
}
