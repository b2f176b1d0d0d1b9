// The joint excitation design (design/joint_excitation.h): the information
// it predicts against a Monte Carlo of the periodic estimate's least-squares
// fit written here (and its closed form, to 1 %), the D-optimum against the equivalence theorem, the
// limits on a fine grid, and a design that beats the flat multisine.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>
#include <random>

#include "design/joint_excitation.h"

using namespace driveid;

namespace {

JointParameters Prior() {
  JointParameters p;
  p.motor_inertia = 0.5;
  p.link_inertia = 1.5;
  p.stiffness = 2000.0;
  p.damping = 2.0;
  p.motor_viscous = 6.0;
  return p;
}

JointDesignOptions Options() {
  JointDesignOptions o;
  o.duration = 20.0;
  o.max_torque = 2.0;
  o.max_speed = 5.0;
  o.noise = 0.02;
  o.torque_noise = 0.002;
  o.free = {"motor_inertia", "link_inertia", "stiffness", "damping"};
  return o;
}

// The motor-rate response per logged torque written apart from models/joint.h.
std::complex<double> Rate(const JointParameters& p, double n, double w) {
  const std::complex<double> s(0.0, w);
  const auto k = p.damping * s + p.stiffness;
  const auto am = p.motor_inertia * s * s + p.motor_viscous * s + k;
  const auto al = p.link_inertia * s * s + p.link_viscous * s + k;
  return n * n * al / (am * al - k * k) * s;
}

}  // namespace

TEST_CASE("joint design: D-optimum meets the equivalence theorem and beats the flat multisine", "[design]") {
  const JointDesign d = DesignJointExcitation(Prior(), 10.0, Options());
  CHECK(d.equivalence < 1.001);
  REQUIRE(d.designed.predicted_std.size() == 4);
  // Within the limits on the logging grid and on a 20x finer one.
  CHECK(d.designed.peak_torque <= 0.99 * 2.0 + 1e-12);
  CHECK(d.designed.peak_speed <= 0.95 * 5.0 + 1e-12);
  CHECK(std::max(d.designed.peak_torque / 1.98, d.designed.peak_speed / 4.75) == Approx(1.0));
  const std::vector<double> fine = SampleJointExcitation(d, d.designed, 20000.0, d.period);
  double peak = 0.0;
  for (double v : fine) peak = std::max(peak, std::abs(v));
  CHECK(peak <= 2.0 * 1.01);
  // The same rms for the naive multisine, and every std smaller by the design.
  CHECK(d.naive.rms == Approx(d.designed.rms));
  for (std::size_t j = 0; j < 4; ++j) CHECK(d.designed.predicted_std[j] < d.naive.predicted_std[j]);
  CHECK(d.naive.geometric_mean_relative_std / d.designed.geometric_mean_relative_std > 2.0);
}

TEST_CASE("joint design: D_s on targets meets its equivalence theorem and favours them", "[design]") {
  JointDesignOptions o = Options();
  const JointDesign all = DesignJointExcitation(Prior(), 10.0, o);
  o.targets = {"stiffness", "damping"};
  const JointDesign some = DesignJointExcitation(Prior(), 10.0, o);
  CHECK(some.equivalence < 1.001);
  // The targets' generalised variance is smaller than under plain D.
  const auto det2 = [](const JointDesignCandidate& c) {
    return c.covariance(2, 2) * c.covariance(3, 3) - c.covariance(2, 3) * c.covariance(3, 2);
  };
  CHECK(det2(some.designed) < det2(all.designed));
}

TEST_CASE("joint design: predicted std equals a Monte Carlo of the line fit", "[design]") {
  // Periodic estimate at each line: H_l (1 + e_l), e_l complex Gaussian with
  // Var = 4 (sigma_v^2 / |H_l|^2 + sigma_u^2) / (M N A_l^2); Gauss-Newton on ln H over ln p by
  // finite differences of Rate(), 200 repeats.
  const JointParameters prior = Prior();
  JointDesignOptions o = Options();
  const JointDesign d = DesignJointExcitation(prior, 10.0, o);
  const double m_periods = d.periods - 1, n_samples = o.period * o.rate;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  double* members[4] = {nullptr, nullptr, nullptr, nullptr};
  JointParameters p = prior;
  members[0] = &p.motor_inertia;
  members[1] = &p.link_inertia;
  members[2] = &p.stiffness;
  members[3] = &p.damping;
  const std::size_t lines = d.frequency.size();
  Eigen::MatrixXd jac(2 * lines, 4);
  Eigen::VectorXd sd(2 * lines);
  for (std::size_t l = 0; l < lines; ++l) {
    const double w = 2.0 * M_PI * d.frequency[l];
    const auto h0 = std::log(Rate(prior, 10.0, w));
    for (int j = 0; j < 4; ++j) {
      p = prior;
      *members[j] *= 1.0 + 1e-6;
      const auto dh = (std::log(Rate(p, 10.0, w)) - h0) / 1e-6;
      jac(2 * l, j) = dh.real();
      jac(2 * l + 1, j) = dh.imag();
    }
    const double a = d.designed.amplitude[l];
    const double var = 4.0 / (m_periods * n_samples * a * a) *
                       (o.noise * o.noise / std::norm(Rate(prior, 10.0, w)) + o.torque_noise * o.torque_noise);
    sd(2 * l) = sd(2 * l + 1) = std::sqrt(0.5 * var);
  }
  const Eigen::MatrixXd weighted = sd.cwiseInverse().asDiagonal() * jac;
  const Eigen::MatrixXd solve = (weighted.transpose() * weighted).inverse() * weighted.transpose();
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(4), square = Eigen::VectorXd::Zero(4);
  const int repeats = 400;
  for (int r = 0; r < repeats; ++r) {
    Eigen::VectorXd e(2 * lines);
    for (Eigen::Index i = 0; i < e.size(); ++i) e(i) = normal(rng);  // already in std units
    const Eigen::VectorXd x = solve * e;
    sum += x;
    square += x.cwiseProduct(x);
  }
  // The covariance of that fit in closed form, (W^T W)^-1 (e has unit
  // variance): the predicted std must hold it to 1 %, so that counting a
  // period that has not settled (-5 % at 10 periods) fails here.
  const Eigen::MatrixXd exact = (weighted.transpose() * weighted).inverse();
  for (int j = 0; j < 4; ++j) {
    const double mc = std::sqrt(square(j) / repeats - std::pow(sum(j) / repeats, 2)) * d.prior[j];
    CHECK(mc == Approx(d.designed.predicted_std[j]).epsilon(0.12));
    CHECK(std::sqrt(exact(j, j)) * d.prior[j] == Approx(d.designed.predicted_std[j]).epsilon(0.01));
  }
  CHECK(d.periods >= 5);
}

TEST_CASE("joint design: refusals name the option", "[design]") {
  JointDesignOptions o = Options();
  std::string error;
  o.duration = 4.0;
  CHECK_FALSE(o.IsValid(&error));
  CHECK(error.find("duration") != std::string::npos);
  o = Options();
  o.free = {"motor_coulomb"};
  CHECK_THROWS_WITH(DesignJointExcitation(Prior(), 10.0, o), Catch::Contains("motor_coulomb"));
  o = Options();
  o.band_low = 100.0;
  o.band_high = 100.2;
  CHECK_THROWS_WITH(DesignJointExcitation(Prior(), 10.0, o), Catch::Contains("band"));
}
