#include "control/speed_loop.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include "core/errors.h"
#include "core/option_check.h"

namespace driveid {

bool SpeedLoopSettings::IsValid(std::string* error) const {
  return OptionCheck(error)
      .Require(Positive(period), "‹period›", period, "period > 0 s")
      .Require(phase_margin_deg > 0.0 && phase_margin_deg < 90.0, "‹phase_margin›", phase_margin_deg,
               "0 < phase margin < 90 deg")
      .Require(NotNegative(min_gain_margin_db), "gain margin", min_gain_margin_db, ">= 0 dB")
      .Require(NotNegative(min_modulus_margin), "modulus margin", min_modulus_margin, ">= 0")
      .Require(NotNegative(notch_width_hz), "‹notch_width›", notch_width_hz, ">= 0 Hz (0: from the resonance's std)")
      .Require(NotNegative(resonance_std_hz), "resonance std", resonance_std_hz, ">= 0 Hz");
}

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

// (1 + x)^a (1 - x)^b as a polynomial in x, lowest power first.
Polynomial Binomials(int plus, int minus) {
  Polynomial out = {1.0};
  for (int i = 0; i < plus; ++i) out = Multiply(out, {1.0, 1.0});
  for (int i = 0; i < minus; ++i) out = Multiply(out, {1.0, -1.0});
  return out;
}

// P(s) (1 + x)^N with s = K (1 - x) / (1 + x), x = z^-1: P highest power
// first, of degree at most N; the result lowest power of x first.
Polynomial TustinPolynomial(const Polynomial& p, double gain, int order) {
  Polynomial out(static_cast<std::size_t>(order) + 1, 0.0);
  const int degree = static_cast<int>(p.size()) - 1;
  for (int i = 0; i <= degree; ++i) {
    const int power = degree - i;  // of s
    const Polynomial term = Binomials(order - power, power);
    for (std::size_t j = 0; j < term.size(); ++j) out[j] += p[static_cast<std::size_t>(i)] * std::pow(gain, power) * term[j];
  }
  return out;
}

// The joint from the log torque u to the motor speed y = n w_m, states
// (theta_m - theta_l, w_m, w_l) on the link side, sampled exactly with the
// zero-order hold and the input delayed by D = d T + e (0 <= e < T):
// x[k+1] = Phi x[k] + Gamma0 u[k-d] + Gamma1 u[k-d-1] (Astrom & Wittenmark),
// Gamma0 = int_0^(T-e) e^(A s) ds B, Gamma1 = e^(A (T-e)) int_0^e e^(A s) ds B.
struct SampledPlant {
  Eigen::Matrix3d phi;
  Eigen::Vector3d gamma0, gamma1;
  Eigen::RowVector3d output;
  int whole = 0;  // d
};

SampledPlant SamplePlant(const SpeedLoopPlant& plant, double period, double delay) {
  const JointParameters& p = plant.joint;
  const double n = plant.gear_ratio;
  Eigen::Matrix4d augmented = Eigen::Matrix4d::Zero();
  augmented.block<3, 3>(0, 0) << 0.0, 1.0, -1.0,  //
      -p.stiffness / p.motor_inertia, -(p.damping + p.motor_viscous) / p.motor_inertia, p.damping / p.motor_inertia,  //
      p.stiffness / p.link_inertia, p.damping / p.link_inertia, -(p.damping + p.link_viscous) / p.link_inertia;
  augmented(1, 3) = n / p.motor_inertia;
  const auto hold = [&](double h, Eigen::Matrix3d& phi, Eigen::Vector3d& gamma) {
    const Eigen::Matrix4d e = (augmented * h).exp();
    phi = e.block<3, 3>(0, 0);
    gamma = e.block<3, 1>(0, 3);
  };
  SampledPlant out;
  out.whole = static_cast<int>(std::floor(delay / period + 1e-9));
  const double fraction = std::max(0.0, delay - out.whole * period);
  Eigen::Matrix3d phi_rest, phi_fraction;
  Eigen::Vector3d gamma_period, gamma_fraction;
  hold(period, out.phi, gamma_period);  // Phi over a whole period (its Gamma is not one of the two)
  hold(period - fraction, phi_rest, out.gamma0);
  hold(fraction, phi_fraction, gamma_fraction);
  out.gamma1 = phi_rest * gamma_fraction;
  out.output << 0.0, n, 0.0;
  return out;
}

// The loop as a drive runs it, state (x, the controller's transposed direct
// form w1..w3, past commands u[k-1] .. u[k-d-1]): s[k+1] = M s[k] + R r[k],
// with the measured speed n w_m = x(1) n.
struct SampledLoop {
  Eigen::MatrixXd transition;
  Eigen::VectorXd reference;
};

SampledLoop MakeSampledLoop(const SpeedLoopPlant& plant, const PiNotch& c, double period) {
  const SampledPlant g = SamplePlant(plant, period, period + plant.delay);  // one period of computation
  Polynomial b, a;
  c.Discrete(period, b, a);
  const int order = static_cast<int>(a.size()) - 1;  // 3
  const int history = g.whole + 1;                   // u[k-1] .. u[k-d-1]
  const int size = 3 + order + history;
  SampledLoop loop;
  loop.transition = Eigen::MatrixXd::Zero(size, size);
  loop.reference = Eigen::VectorXd::Zero(size);
  // u[k] = b0 (r - y) + w1, as a row over the state (and r).
  Eigen::RowVectorXd command = Eigen::RowVectorXd::Zero(size);
  command.head<3>() = -b[0] * g.output;
  command(3) = 1.0;
  const double command_r = b[0];
  const auto past = [&](int j) { return 3 + order + j - 1; };  // u[k-j], j >= 1
  auto& m = loop.transition;
  m.block<3, 3>(0, 0) = g.phi;
  m.block(0, past(g.whole), 3, 1) += g.gamma0;
  m.block(0, past(g.whole + 1), 3, 1) += g.gamma1;
  for (int i = 0; i < order; ++i) {  // w_i[k+1] = b_i e - a_i u + w_(i+1)
    const int row = 3 + i;
    const std::size_t k = static_cast<std::size_t>(i) + 1;
    m.row(row) = -a[k] * command;
    m.block(row, 0, 1, 3) += -b[k] * g.output;
    if (i + 1 < order) m(row, row + 1) += 1.0;
    loop.reference(row) = b[k] - a[k] * command_r;
  }
  m.row(past(1)) = command;
  loop.reference(past(1)) = command_r;
  for (int j = 2; j <= history; ++j) m(past(j), past(j - 1)) = 1.0;
  return loop;
}

Complex Loop(const SpeedLoopPlant& plant, const PiNotch& c, double period, double omega) {
  const Complex p = CalcJointResponse(plant.joint, plant.gear_ratio, omega, ResponseQuantity::kRate).motor;
  return p * c.Evaluate(omega) * std::exp(Complex(0.0, -omega * plant.LoopDelay(period)));
}

void CheckPlant(const SpeedLoopPlant& plant) {
  const JointParameters& p = plant.joint;
  if (!(p.motor_inertia > 0.0) || !(p.link_inertia > 0.0) || !(p.stiffness > 0.0) || !(p.damping >= 0.0) ||
      !(p.motor_viscous >= 0.0) || !(p.link_viscous >= 0.0) || !(plant.gear_ratio > 0.0) || !(plant.delay >= 0.0) ||
      !std::isfinite(plant.delay)) {
    throw InputError("speed loop: the joint needs J_m, J_l, k > 0, d, b_m, b_l >= 0, a gear ratio and a delay >= 0");
  }
}

// At the nominal plant: every requirement; at the edge of the 95 % region:
// stable, the gain and modulus margins, and the phase margin within 10 deg.
bool Meets(const LoopMargins& m, const SpeedLoopSettings& s, bool edge) {
  return m.stable && m.phase_margin_deg >= s.phase_margin_deg - (edge ? 10.0 : 0.0) &&
         m.gain_margin_db >= s.min_gain_margin_db && m.modulus_margin >= s.min_modulus_margin;
}

// The smallest of the margins' relative excess over their requirements
// (negative: one is missed); unstable loops rank below every stable one.
double Slack(const LoopMargins& m, const SpeedLoopSettings& s) {
  if (!m.stable) return -1e300;
  return std::min({(m.phase_margin_deg - s.phase_margin_deg) / s.phase_margin_deg,
                   (m.gain_margin_db - s.min_gain_margin_db) / s.min_gain_margin_db,
                   (m.modulus_margin - s.min_modulus_margin) / s.min_modulus_margin});
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

void PiNotch::Discrete(double period, std::vector<double>& numerator, std::vector<double>& denominator) const {
  const double wn = 2.0 * M_PI * notch_hz;
  // Prewarped at the notch while it lies below the Nyquist frequency.
  const double gain = wn * period < 0.9 * M_PI && wn > 0.0 ? wn / std::tan(wn * period / 2.0) : 2.0 / period;
  const Polynomial num = Numerator(), den = Denominator();
  const int order = static_cast<int>(std::max(num.size(), den.size())) - 1;
  numerator = TustinPolynomial(num, gain, order);
  denominator = TustinPolynomial(den, gain, order);
  const double lead = denominator[0];
  for (double& v : numerator) v /= lead;
  for (double& v : denominator) v /= lead;
}

double DiscreteLoopRadius(const SpeedLoopPlant& plant, const PiNotch& c, double period) {
  CheckPlant(plant);
  if (!(period > 0.0) || plant.delay > 1000.0 * period) {
    throw OptionError("speed loop: a period > 0 and a delay of at most 1000 periods are required");
  }
  const SampledLoop loop = MakeSampledLoop(plant, c, period);
  if (!loop.transition.allFinite()) return std::numeric_limits<double>::infinity();
  return loop.transition.eigenvalues().cwiseAbs().maxCoeff();
}

LoopMargins EvaluateSpeedLoop(const SpeedLoopPlant& plant, const PiNotch& c, double period) {
  CheckPlant(plant);
  const double nyquist = M_PI / period;
  LoopMargins m;
  m.stable = DiscreteLoopRadius(plant, c, period) < 1.0;
  m.phase_margin_deg = std::numeric_limits<double>::infinity();
  m.gain_margin_db = std::numeric_limits<double>::infinity();
  m.modulus_margin = std::numeric_limits<double>::infinity();
  const int points = 8000;
  const double low = 2.0 * M_PI * 1e-3;
  double previous_magnitude = 0.0, previous_phase = 0.0, phase_offset = 0.0;
  for (int i = 0; i < points; ++i) {
    const double omega = low * std::pow(nyquist / low, static_cast<double>(i) / (points - 1));
    const Complex l = Loop(plant, c, period, omega);
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
  RequireValid(s);
  SpeedLoopDesign best;
  double closest_slack = -std::numeric_limits<double>::infinity();
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
    c.kp = 1.0 / std::abs(Loop(plant, c, s.period, wc));
    const LoopMargins nominal = EvaluateSpeedLoop(plant, c, s.period);
    const double slack = Slack(nominal, s);
    if (!best.met && slack > closest_slack) closest_slack = slack, best.closest = nominal;
    if (!Meets(nominal, s, false)) continue;
    best.nominal_only_crossover_hz = std::max(best.nominal_only_crossover_hz, nominal.crossover_hz);
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
    if (!best.met || nominal.crossover_hz > best.nominal.crossover_hz) {
      best.controller = c;
      best.nominal = nominal;
      best.worst = worst;
      best.met = true;
    }
  }
  return best;
}

std::vector<std::complex<double>> OpenLoopResponse(const SpeedLoopPlant& plant, const PiNotch& controller, double period,
                                                   const std::vector<double>& frequencies_hz) {
  std::vector<std::complex<double>> out;
  for (double f : frequencies_hz) out.push_back(Loop(plant, controller, period, 2.0 * M_PI * f));
  return out;
}

StepResponse SimulateSpeedStep(const SpeedLoopPlant& plant, const PiNotch& c, double period, double duration) {
  CheckPlant(plant);
  const SampledLoop loop = MakeSampledLoop(plant, c, period);
  StepResponse out;
  Eigen::VectorXd state = Eigen::VectorXd::Zero(loop.transition.rows());
  const auto steps = static_cast<std::size_t>(std::ceil(duration / period));
  for (std::size_t k = 0; k <= steps; ++k) {
    out.time.push_back(static_cast<double>(k) * period);
    out.speed.push_back(plant.gear_ratio * state(1));
    state = loop.transition * state + loop.reference;
  }
  return out;
}

}  // namespace driveid
