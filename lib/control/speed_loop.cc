#include "control/speed_loop.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

namespace driveid {
namespace {

using Complex = std::complex<double>;
using Polynomial = std::vector<double>;  // highest power first

Polynomial Multiply(const Polynomial& a, const Polynomial& b) {
  Polynomial out(a.size() + b.size() - 1, 0.0);
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) out[i + j] += a[i] * b[j];
  }
  return out;
}

Polynomial Add(Polynomial a, Polynomial b) {
  if (a.size() < b.size()) std::swap(a, b);
  const std::size_t shift = a.size() - b.size();
  for (std::size_t i = 0; i < b.size(); ++i) a[shift + i] += b[i];
  return a;
}

// Pade approximant of e^(-s tau) of order 4: N(s) / N(-s).
void PadeDelay(double tau, Polynomial& numerator, Polynomial& denominator) {
  constexpr int n = 4;
  numerator.assign(n + 1, 0.0);
  denominator.assign(n + 1, 0.0);
  const auto factorial = [](int k) { return std::tgamma(k + 1.0); };
  for (int k = 0; k <= n; ++k) {
    const double c = factorial(2 * n - k) * factorial(n) / (factorial(2 * n) * factorial(k) * factorial(n - k)) *
                     std::pow(tau, k);
    numerator[n - k] = (k % 2 ? -c : c);
    denominator[n - k] = c;
  }
}

bool StableRoots(Polynomial p) {
  while (p.size() > 1 && p.front() == 0.0) p.erase(p.begin());
  const std::size_t degree = p.size() - 1;
  if (degree == 0) return true;
  // s = w0 z with w0 the geometric mean of the roots' magnitudes: the
  // coefficients of a loop with a stiff spring span many decades otherwise.
  const double w0 = std::abs(p.back()) > 0.0 ? std::pow(std::abs(p.back() / p.front()), 1.0 / static_cast<double>(degree)) : 1.0;
  const double lead = p[0];
  for (std::size_t j = 0; j <= degree; ++j) p[j] /= lead * std::pow(w0, static_cast<double>(j));
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(degree, degree);
  for (std::size_t j = 0; j < degree; ++j) companion(0, j) = -p[j + 1] / p[0];
  for (std::size_t i = 1; i < degree; ++i) companion(i, i - 1) = 1.0;
  const Eigen::VectorXcd roots = companion.eigenvalues();
  for (Eigen::Index i = 0; i < roots.size(); ++i) {
    if (!(roots[i].real() < 0.0)) return false;
  }
  return true;
}

// The plant from the log torque to the motor speed: n^2 A_l s / Delta with the
// common s cancelled: n^2 A_l / (Delta / s) (models/joint.h).
void PlantPolynomials(const SpeedLoopPlant& plant, Polynomial& numerator, Polynomial& denominator) {
  const JointParameters& p = plant.joint;
  const double n2 = plant.gear_ratio * plant.gear_ratio;
  const double a = p.damping + p.motor_viscous, b = p.damping + p.link_viscous;
  numerator = {n2 * p.link_inertia, n2 * b, n2 * p.stiffness};
  denominator = {p.motor_inertia * p.link_inertia, p.motor_inertia * b + p.link_inertia * a,
                 p.stiffness * (p.motor_inertia + p.link_inertia) + a * b - p.damping * p.damping,
                 p.stiffness * (p.motor_viscous + p.link_viscous)};
}

bool ClosedLoopStable(const SpeedLoopPlant& plant, const PiNotch& c, double tau) {
  Polynomial pn, pd, dn, dd;
  PlantPolynomials(plant, pn, pd);
  PadeDelay(tau, dn, dd);
  const Polynomial open_numerator = Multiply(Multiply(pn, c.Numerator()), dn);
  const Polynomial open_denominator = Multiply(Multiply(pd, c.Denominator()), dd);
  return StableRoots(Add(open_denominator, open_numerator));
}

Complex Loop(const SpeedLoopPlant& plant, const PiNotch& c, double tau, double omega) {
  const Complex p = CalcJointResponse(plant.joint, plant.gear_ratio, omega, ResponseQuantity::kRate).motor;
  return p * c.Evaluate(omega) * std::exp(Complex(0.0, -omega * tau));
}

void CheckPlant(const SpeedLoopPlant& plant) {
  const JointParameters& p = plant.joint;
  if (!(p.motor_inertia > 0.0) || !(p.link_inertia > 0.0) || !(p.stiffness > 0.0) || !(p.damping >= 0.0) ||
      !(p.motor_viscous >= 0.0) || !(p.link_viscous >= 0.0) || !(plant.gear_ratio > 0.0)) {
    throw std::invalid_argument("speed loop: the joint needs J_m, J_l, k > 0, d, b_m, b_l >= 0 and a gear ratio");
  }
}

// At the nominal plant: every requirement; at the edge of the 95 % region:
// stable, the gain and modulus margins, and the phase margin within 10 deg.
bool Meets(const LoopMargins& m, const SpeedLoopSettings& s, bool edge) {
  return m.stable && m.phase_margin_deg >= s.phase_margin_deg - (edge ? 10.0 : 0.0) &&
         m.gain_margin_db >= s.min_gain_margin_db && m.modulus_margin >= s.min_modulus_margin;
}

}  // namespace

std::vector<double> PiNotch::Numerator() const {
  const double wn = 2.0 * M_PI * notch_hz;
  const double zeta_pole = M_PI * notch_width_hz / wn;  // width 2 z_p w_n [rad/s]
  const double zeta_zero = zeta_pole * std::pow(10.0, -notch_depth_db / 20.0);
  return Multiply({kp, kp * integral_corner}, {1.0, 2.0 * zeta_zero * wn, wn * wn});
}

std::vector<double> PiNotch::Denominator() const {
  const double wn = 2.0 * M_PI * notch_hz;
  const double zeta_pole = M_PI * notch_width_hz / wn;
  return {1.0, 2.0 * zeta_pole * wn, wn * wn, 0.0};
}

Complex PiNotch::Evaluate(double omega) const {
  const Complex s(0.0, omega);
  Complex num = 0.0, den = 0.0;
  for (double c : Numerator()) num = num * s + c;
  for (double c : Denominator()) den = den * s + c;
  return num / den;
}

LoopMargins EvaluateSpeedLoop(const SpeedLoopPlant& plant, const PiNotch& c, double period) {
  CheckPlant(plant);
  const double tau = 1.5 * period, nyquist = M_PI / period;
  LoopMargins m;
  m.stable = ClosedLoopStable(plant, c, tau);
  m.phase_margin_deg = std::numeric_limits<double>::infinity();
  m.gain_margin_db = std::numeric_limits<double>::infinity();
  m.modulus_margin = std::numeric_limits<double>::infinity();
  const int points = 8000;
  const double low = 2.0 * M_PI * 1e-3;
  double previous_magnitude = 0.0, previous_phase = 0.0, phase_offset = 0.0;
  for (int i = 0; i < points; ++i) {
    const double omega = low * std::pow(nyquist / low, static_cast<double>(i) / (points - 1));
    const Complex l = Loop(plant, c, tau, omega);
    const double magnitude = std::abs(l);
    double phase = std::arg(l) + phase_offset;
    if (i > 0) {  // unwrap
      while (phase - previous_phase > M_PI) phase -= 2.0 * M_PI, phase_offset -= 2.0 * M_PI;
      while (phase - previous_phase < -M_PI) phase += 2.0 * M_PI, phase_offset += 2.0 * M_PI;
    }
    m.modulus_margin = std::min(m.modulus_margin, std::abs(1.0 + l));
    if (i > 0 && (previous_magnitude - 1.0) * (magnitude - 1.0) <= 0.0 && previous_magnitude != magnitude) {
      if (m.crossover_hz == 0.0) m.crossover_hz = omega / (2.0 * M_PI);
      // The angle between L and -1 (stability itself is judged on the poles).
      const double margin = 180.0 - std::abs(std::remainder(phase * 180.0 / M_PI, 360.0));
      m.phase_margin_deg = std::min(m.phase_margin_deg, margin);
    }
    // Phase crossings of an odd multiple of -180 degrees.
    if (i > 0) {
      const double a = (previous_phase / M_PI - 1.0) / 2.0, b = (phase / M_PI - 1.0) / 2.0;
      if (std::floor(a) != std::floor(b)) m.gain_margin_db = std::min(m.gain_margin_db, -20.0 * std::log10(magnitude));
    }
    previous_magnitude = magnitude;
    previous_phase = phase;
  }
  return m;
}

SpeedLoopDesign DesignSpeedLoop(const SpeedLoopPlant& plant, const std::vector<SpeedLoopPlant>& region,
                                const SpeedLoopSettings& s) {
  CheckPlant(plant);
  if (!(s.period > 0.0) || !(s.phase_margin_deg > 0.0) || !(s.phase_margin_deg < 90.0)) {
    throw std::invalid_argument("speed loop: period > 0 and a phase margin between 0 and 90 degrees are required");
  }
  SpeedLoopDesign best;
  PiNotch c;
  c.notch_hz = JointResonance(plant.joint) / (2.0 * M_PI);
  c.notch_width_hz = s.notch_width_hz > 0.0 ? s.notch_width_hz
                                            : std::max(0.3 * c.notch_hz, 2.0 * 1.96 * s.resonance_std_hz);
  const double nyquist = M_PI / s.period;
  const double low = 0.02 * JointAntiresonance(plant.joint);
  const int candidates = 120;
  for (int i = 0; i < candidates; ++i) {
    const double wc = low * std::pow(0.2 * nyquist / low, static_cast<double>(i) / (candidates - 1));
    c.integral_corner = wc / 4.0;
    c.kp = 1.0;
    c.kp = 1.0 / std::abs(Loop(plant, c, 1.5 * s.period, wc));
    const LoopMargins nominal = EvaluateSpeedLoop(plant, c, s.period);
    if (!Meets(nominal, s, false)) continue;
    LoopMargins worst = nominal;
    bool robust = true;
    for (const auto& edge : region) {
      const LoopMargins m = EvaluateSpeedLoop(edge, c, s.period);
      robust = robust && Meets(m, s, true);
      worst.stable = worst.stable && m.stable;
      worst.phase_margin_deg = std::min(worst.phase_margin_deg, m.phase_margin_deg);
      worst.gain_margin_db = std::min(worst.gain_margin_db, m.gain_margin_db);
      worst.modulus_margin = std::min(worst.modulus_margin, m.modulus_margin);
      worst.crossover_hz = std::min(worst.crossover_hz, m.crossover_hz);
      if (!robust) break;
    }
    if (!robust) continue;
    if (!best.met || nominal.crossover_hz > best.nominal.crossover_hz) best = {c, nominal, worst, true};
  }
  return best;
}

std::vector<std::complex<double>> OpenLoopResponse(const SpeedLoopPlant& plant, const PiNotch& controller, double period,
                                                   const std::vector<double>& frequencies_hz) {
  std::vector<std::complex<double>> out;
  for (double f : frequencies_hz) out.push_back(Loop(plant, controller, 1.5 * period, 2.0 * M_PI * f));
  return out;
}

StepResponse SimulateSpeedStep(const SpeedLoopPlant& plant, const PiNotch& c, double period, double duration) {
  CheckPlant(plant);
  const JointParameters& p = plant.joint;
  const double n = plant.gear_ratio;
  // x = (theta_m, theta_m', theta_l, theta_l'), link side; input the log torque (tau_m = n tau).
  Eigen::Matrix<double, 5, 5> augmented = Eigen::Matrix<double, 5, 5>::Zero();
  augmented.block<4, 4>(0, 0) << 0, 1, 0, 0,  //
      -p.stiffness / p.motor_inertia, -(p.damping + p.motor_viscous) / p.motor_inertia, p.stiffness / p.motor_inertia,
      p.damping / p.motor_inertia,  //
      0, 0, 0, 1,                   //
      p.stiffness / p.link_inertia, p.damping / p.link_inertia, -p.stiffness / p.link_inertia,
      -(p.damping + p.link_viscous) / p.link_inertia;
  augmented(1, 4) = n / p.motor_inertia;
  const Eigen::Matrix<double, 5, 5> e = (augmented * period).exp();
  const Eigen::Matrix4d phi = e.block<4, 4>(0, 0);
  const Eigen::Vector4d gamma = e.block<4, 1>(0, 4);
  // C(s) in controllable canonical form, then Tustin: (I - A h/2)^-1.
  const std::vector<double> num = c.Numerator(), den = c.Denominator();
  const Eigen::Index m = static_cast<Eigen::Index>(den.size()) - 1;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, m);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(m), cc(m);
  for (Eigen::Index j = 0; j < m; ++j) a(0, j) = -den[j + 1] / den[0];
  for (Eigen::Index i = 1; i < m; ++i) a(i, i - 1) = 1.0;
  b(0) = 1.0;
  const double direct = num.size() == den.size() ? num[0] / den[0] : 0.0;
  for (Eigen::Index j = 0; j < m; ++j) {
    const std::size_t k = num.size() - static_cast<std::size_t>(m) + static_cast<std::size_t>(j);
    cc(j) = (k < num.size() ? num[k] / den[0] : 0.0) - direct * den[j + 1] / den[0];
  }
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(m, m);
  const Eigen::MatrixXd inverse = (identity - a * period / 2.0).inverse();
  const Eigen::MatrixXd ad = inverse * (identity + a * period / 2.0);
  const Eigen::VectorXd bd = inverse * b * period;
  // Output of the Tustin form: y = cc (x + bd e / 2) + direct e (the trapezoid's half step).
  StepResponse out;
  Eigen::Vector4d x = Eigen::Vector4d::Zero();
  Eigen::VectorXd z = Eigen::VectorXd::Zero(m);
  double applied = 0.0;
  const auto steps = static_cast<std::size_t>(std::ceil(duration / period));
  for (std::size_t k = 0; k <= steps; ++k) {
    const double speed = n * x(1);
    out.time.push_back(static_cast<double>(k) * period);
    out.speed.push_back(speed);
    const double error = 1.0 - speed;
    const double command = cc.dot(z + bd * error / 2.0) + direct * error;
    z = ad * z + bd * error;
    x = phi * x + gamma * applied;
    applied = command;  // one period late
  }
  return out;
}

}  // namespace driveid
