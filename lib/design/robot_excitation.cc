#include "design/robot_excitation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "design/axis_excitation.h"
#include "design/nelder_mead.h"
#include "models/serial_dynamics.h"

namespace driveid {

bool RobotDesignOptions::IsValid(std::string* error) const {
  const auto optional = [](double v) { return v == 0.0 || Positive(v); };
  return OptionCheck(error)
      .Require(Positive(duration), "‹duration›", duration, "duration > 0 s")
      .Require(Positive(rate), "‹rate›", rate, "rate > 0 Hz")
      .Require(period == 0.0 || (Positive(period) && period <= duration), "‹period›", period, "0 < period <= duration")
      .Require(harmonics >= 2 && harmonics <= 20, "‹harmonics›", harmonics, "2 <= harmonics <= 20")
      .Require(optional(max_position), "‹max_position›", max_position, "> 0")
      .Require(optional(max_rate), "‹max_speed›", max_rate, "> 0")
      .Require(optional(max_acceleration), "‹max_acceleration›", max_acceleration, "> 0")
      .Require(optional(max_torque), "‹max_torque›", max_torque, "> 0")
      .Require(criterion == "d" || criterion == "a", "‹criterion› " + criterion + ": choose d or a")
      .Require(evaluations >= 10 && evaluations <= 1000000, "‹evaluations›", evaluations, "10 <= evaluations <= 1e6");
}

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct JointLimits {
  double lower = -kInfinity, upper = kInfinity, position = kInfinity, rate = kInfinity, acceleration = kInfinity,
         torque = kInfinity;
};

std::vector<JointLimits> Limits(const SerialRobot& robot, const RobotDesignOptions& o) {
  std::vector<JointLimits> out;
  for (const SerialJoint& j : robot.joints) {
    JointLimits l;
    l.lower = j.lower;
    l.upper = j.upper;
    if (o.max_position > 0.0) l.position = o.max_position;
    l.rate = o.max_rate > 0.0 ? std::min(o.max_rate, j.velocity_limit) : j.velocity_limit;
    if (o.max_acceleration > 0.0) l.acceleration = o.max_acceleration;
    l.torque = o.max_torque > 0.0 ? std::min(o.max_torque, j.effort_limit) : j.effort_limit;
    if (!std::isfinite(l.upper - l.lower) && !std::isfinite(l.position)) {
      throw OptionError(fmt::format("joint '{}' has no position limits in the URDF: give ‹max_position›", j.name));
    }
    if (!std::isfinite(l.rate)) {
      throw OptionError(fmt::format("joint '{}' has no velocity limit in the URDF: give ‹max_speed›", j.name));
    }
    out.push_back(l);
  }
  return out;
}

// The problem over one period on a grid.
struct Problem {
  const SerialRobot* robot = nullptr;
  Eigen::VectorXd theta;
  std::vector<std::size_t> base;
  std::vector<double> weight;  // 1 / sigma_j^2
  std::vector<JointLimits> limits;
  std::vector<double> value_scale;  // A: |prior beta|
  double base_frequency = 0.0;
  std::vector<int> harmonics;
  std::size_t shape_size = 0;       // per joint: 2 (K - 1)
  double samples_per_grid = 0.0;    // N / M
  bool a_criterion = false;
};

struct Candidate {
  std::vector<FourierReference> reference;  // scaled, about the start
  std::vector<double> start;
  std::vector<std::string> binding;
  std::vector<std::vector<ReferenceSample3>> at;  // [joint][grid point], q about the start
  Eigen::MatrixXd information;
  std::vector<double> peak_torque;
  bool ok = true;
};

std::vector<double> Grid(double period, std::size_t points) {
  std::vector<double> t(points);
  for (std::size_t m = 0; m < points; ++m) t[m] = period * static_cast<double>(m) / static_cast<double>(points);
  return t;
}

// Scales every joint's shape to its kinematic limits.
Candidate Scale(const Problem& p, const std::vector<double>& x, const std::vector<double>& grid) {
  const std::size_t n = p.robot->size();
  Candidate c;
  for (std::size_t j = 0; j < n; ++j) {
    const std::vector<double> free(x.begin() + static_cast<long>(j * p.shape_size),
                                   x.begin() + static_cast<long>((j + 1) * p.shape_size));
    const FourierReference shape = MakeRestingReference(p.base_frequency, p.harmonics, free);
    double lo = 0.0, hi = 0.0, v = 0.0, a = 0.0;
    for (double t : grid) {
      const ReferenceSample3 s = shape.At(t);
      lo = std::min(lo, s.position);
      hi = std::max(hi, s.position);
      v = std::max(v, std::abs(s.rate));
      a = std::max(a, std::abs(s.acceleration));
    }
    const JointLimits& l = p.limits[j];
    const std::pair<double, const char*> bounds[] = {
        {std::isfinite(l.upper - l.lower) && hi > lo ? (l.upper - l.lower) / (hi - lo) : kInfinity, "position range"},
        {std::max(hi, -lo) > 0.0 ? l.position / std::max(hi, -lo) : kInfinity, "max position"},
        {v > 0.0 ? l.rate / v : kInfinity, "velocity"},
        {a > 0.0 ? l.acceleration / a : kInfinity, "acceleration"}};
    double scale = kInfinity;
    const char* binding = "";
    for (const auto& [s, name] : bounds) {
      if (s < scale) {
        scale = s;
        binding = name;
      }
    }
    scale *= kKinematicMargin;
    if (!std::isfinite(scale) || !(scale > 0.0)) c.ok = false;
    c.reference.push_back(ScaledReference(shape, std::isfinite(scale) ? scale : 0.0));
    c.binding.emplace_back(binding);
    const double centre = std::isfinite(l.upper - l.lower) ? 0.5 * (l.upper + l.lower) : 0.0;
    c.start.push_back(std::isfinite(l.upper - l.lower) ? centre - 0.5 * scale * (hi + lo) : 0.0);
  }
  return c;
}

// Every joint's largest |torque| / its limit along the candidate shrunk by `factor`.
double TorqueRatio(const Problem& p, const Candidate& c, double factor, const std::vector<double>& grid,
                   std::vector<double>* peaks) {
  const std::size_t n = p.robot->size();
  const auto size = static_cast<Eigen::Index>(n);
  Eigen::VectorXd q(size), qd(size), qdd(size);
  Eigen::MatrixXd y(size, static_cast<Eigen::Index>(kSerialColumnsPerJoint * n));
  std::vector<double> peak(n, 0.0);
  for (double t : grid) {
    for (std::size_t j = 0; j < n; ++j) {
      const ReferenceSample3 s = c.reference[j].At(t);
      const auto i = static_cast<Eigen::Index>(j);
      q(i) = c.start[j] + factor * s.position;
      qd(i) = factor * s.rate;
      qdd(i) = factor * s.acceleration;
    }
    CalcSerialRegressor(*p.robot, q, qd, qdd, y);
    const Eigen::VectorXd tau = y * p.theta;
    for (std::size_t j = 0; j < n; ++j) peak[j] = std::max(peak[j], std::abs(tau(static_cast<Eigen::Index>(j))));
  }
  double ratio = 0.0;
  for (std::size_t j = 0; j < n; ++j) ratio = std::max(ratio, peak[j] / (kTorqueMargin * p.limits[j].torque));
  if (peaks) *peaks = peak;
  return ratio;
}

// The information of the base parameters along the candidate.
Eigen::MatrixXd Information(const Problem& p, const std::vector<FourierReference>& reference,
                            const std::vector<double>& start, const std::vector<double>& grid, double per_point,
                            Eigen::MatrixXd* rows) {
  const std::size_t n = p.robot->size(), r = p.base.size();
  const auto size = static_cast<Eigen::Index>(n);
  Eigen::VectorXd q(size), qd(size), qdd(size);
  Eigen::MatrixXd y(size, static_cast<Eigen::Index>(kSerialColumnsPerJoint * n));
  Eigen::MatrixXd info = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(r));
  Eigen::MatrixXd w(size, static_cast<Eigen::Index>(r));
  if (rows) rows->resize(static_cast<Eigen::Index>(grid.size() * n), static_cast<Eigen::Index>(r));
  for (std::size_t m = 0; m < grid.size(); ++m) {
    for (std::size_t j = 0; j < n; ++j) {
      const ReferenceSample3 s = reference[j].At(grid[m]);
      const auto i = static_cast<Eigen::Index>(j);
      q(i) = start[j] + s.position;
      qd(i) = s.rate;
      qdd(i) = s.acceleration;
    }
    CalcSerialRegressor(*p.robot, q, qd, qdd, y);
    for (std::size_t c = 0; c < r; ++c) w.col(static_cast<Eigen::Index>(c)) = y.col(static_cast<Eigen::Index>(p.base[c]));
    for (std::size_t j = 0; j < n; ++j) w.row(static_cast<Eigen::Index>(j)) *= std::sqrt(p.weight[j]);
    info.selfadjointView<Eigen::Lower>().rankUpdate(w.transpose());
    if (rows) rows->middleRows(static_cast<Eigen::Index>(m * n), size) = w;
  }
  info = info.selfadjointView<Eigen::Lower>();
  return per_point * info;
}

// The candidate at the common torque factor, its references shrunk.
Candidate Shrunk(const Problem& p, Candidate c, const std::vector<double>& grid) {
  if (!c.ok) return c;
  double factor = 1.0;
  if (TorqueRatio(p, c, 1.0, grid, nullptr) > 1.0) {
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 12; ++it) {
      const double mid = 0.5 * (lo + hi);
      (TorqueRatio(p, c, mid, grid, nullptr) > 1.0 ? hi : lo) = mid;
    }
    factor = lo;
    for (std::string& b : c.binding) b = "torque";
  }
  if (!(factor > 0.0)) c.ok = false;
  for (auto& ref : c.reference) ref = ScaledReference(ref, factor);
  return c;
}

double Criterion(const Problem& p, const Eigen::MatrixXd& info) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(info);
  const Eigen::VectorXd d = ldlt.vectorD();
  if (ldlt.info() != Eigen::Success || !(d.minCoeff() > 1e-12 * std::max(1.0, d.maxCoeff()))) return 1e300;
  if (!p.a_criterion) return -d.array().log().sum();
  const Eigen::MatrixXd cov = ldlt.solve(Eigen::MatrixXd::Identity(info.rows(), info.cols()));
  double sum = 0.0;
  for (Eigen::Index c = 0; c < cov.rows(); ++c) sum += cov(c, c) / std::pow(p.value_scale[static_cast<std::size_t>(c)], 2);
  return std::log(sum);
}

Problem MakeProblem(const SerialRobot& robot, const Eigen::VectorXd& theta, const std::vector<std::size_t>& base_columns,
                    const std::vector<double>& noise, const RobotDesignOptions& options, double period) {
  const std::size_t n = robot.size();
  Problem p;
  p.robot = &robot;
  p.theta = theta;
  p.base = base_columns;
  for (std::size_t j = 0; j < n; ++j) {
    if (!Positive(noise[j])) {
      throw OptionError(fmt::format("joint '{}': torque noise {}: must be > 0", robot.joints[j].name, noise[j]));
    }
    p.weight.push_back(1.0 / (noise[j] * noise[j]));
  }
  p.limits = Limits(robot, options);
  double largest = 0.0;
  for (std::size_t c : base_columns) largest = std::max(largest, std::abs(theta(static_cast<Eigen::Index>(c))));
  for (std::size_t c : base_columns) {
    p.value_scale.push_back(std::max(std::abs(theta(static_cast<Eigen::Index>(c))), 1e-3 * std::max(largest, 1e-12)));
  }
  p.base_frequency = 1.0 / period;
  for (int k = 1; k <= options.harmonics; ++k) p.harmonics.push_back(k);
  p.shape_size = 2 * static_cast<std::size_t>(options.harmonics - 1);
  p.a_criterion = options.criterion == "a";
  return p;
}

// The prior at rest at the ranges' centres must hold the torque limits.
void RequireRestWithinLimits(const Problem& p) {
  const std::size_t n = p.robot->size();
  const auto size = static_cast<Eigen::Index>(n);
  Eigen::VectorXd q(size);
  for (std::size_t j = 0; j < n; ++j) {
    const JointLimits& l = p.limits[j];
    q(static_cast<Eigen::Index>(j)) = std::isfinite(l.upper - l.lower) ? 0.5 * (l.upper + l.lower) : 0.0;
  }
  Eigen::MatrixXd y(size, static_cast<Eigen::Index>(kSerialColumnsPerJoint * n));
  CalcSerialRegressor(*p.robot, q, Eigen::VectorXd::Zero(size), Eigen::VectorXd::Zero(size), y);
  const Eigen::VectorXd tau = y * p.theta;
  for (std::size_t j = 0; j < n; ++j) {
    const double held = std::abs(tau(static_cast<Eigen::Index>(j)));
    if (held > kTorqueMargin * p.limits[j].torque) {
      throw OptionError(fmt::format("joint '{}': the prior's torque at rest, {:.4g}, exceeds {:g} % of its limit "
                                    "{:.4g}: raise ‹max_torque› or check the URDF's effort limits",
                                    p.robot->joints[j].name, held, 100 * kTorqueMargin, p.limits[j].torque));
    }
  }
}

// The best shape of two Nelder-Mead runs from seeded random starts.
SimplexResult Optimise(const Problem& p, const std::vector<double>& grid, int evaluations, int* spent) {
  const auto evaluate = [&](const std::vector<double>& x) {
    const Candidate c = Shrunk(p, Scale(p, x, grid), grid);
    if (!c.ok) return 1e300;
    return Criterion(p, Information(p, c.reference, c.start, grid, p.samples_per_grid, nullptr));
  };
  std::mt19937_64 rng(20261128);
  std::normal_distribution<double> normal;
  SimplexResult best;
  best.value = kInfinity;
  for (int start = 0; start < 2; ++start) {
    std::vector<double> x0(p.robot->size() * p.shape_size), step(x0.size());
    for (std::size_t i = 0; i < x0.size(); ++i) {
      const double harmonic = static_cast<double>(2 + i % (p.shape_size / 2));  // lines 2..K, a then b
      x0[i] = normal(rng) / harmonic;
      step[i] = 0.3 / harmonic;
    }
    SimplexResult r = MinimiseNelderMead(evaluate, x0, step, 1e-7, evaluations);
    *spent += r.evaluations;
    if (r.value < best.value) best = r;
  }
  if (!(best.value < 1e299)) {
    throw OptionError("no trajectory within the limits determines the base parameters: wider limits or a longer log");
  }
  return best;
}

// Covariance, stds and condition number of the candidate on `fine`.
void Predict(const Problem& p, const Candidate& c, const std::vector<double>& fine, double samples, RobotDesign& design) {
  Eigen::MatrixXd rows;
  const Eigen::MatrixXd info = Information(p, c.reference, c.start, fine, samples / static_cast<double>(fine.size()), &rows);
  design.criterion = Criterion(p, info);
  design.covariance = info.ldlt().solve(Eigen::MatrixXd::Identity(info.rows(), info.cols()));
  for (Eigen::Index k = 0; k < design.covariance.rows(); ++k) design.predicted_std.push_back(std::sqrt(design.covariance(k, k)));
  for (Eigen::Index k = 0; k < rows.cols(); ++k) {
    const double norm = rows.col(k).norm();
    if (norm > 0.0) rows.col(k) /= norm;
  }
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(rows);
  const Eigen::VectorXd s = svd.singularValues();
  design.condition_number = s(s.size() - 1) > 0.0 ? s(0) / s(s.size() - 1) : kInfinity;
}

RobotDesignJoint DesignedJoint(const std::string& name, const Candidate& c, std::size_t j, const std::vector<double>& fine,
                               double peak_torque, const JointLimits& limits) {
  RobotDesignJoint joint;
  joint.name = name;
  joint.rate_limit = limits.rate;
  joint.torque_limit = limits.torque;
  joint.reference = c.reference[j];
  joint.start = c.start[j];
  joint.binding = c.binding[j];
  joint.lowest = joint.highest = joint.start;
  for (double t : fine) {
    const ReferenceSample3 r = joint.reference.At(t);
    joint.lowest = std::min(joint.lowest, joint.start + r.position);
    joint.highest = std::max(joint.highest, joint.start + r.position);
    joint.peak_rate = std::max(joint.peak_rate, std::abs(r.rate));
    joint.peak_acceleration = std::max(joint.peak_acceleration, std::abs(r.acceleration));
  }
  joint.peak_torque = peak_torque;
  return joint;
}

}  // namespace

RobotDesign DesignRobotExcitation(const SerialRobot& robot, const Eigen::VectorXd& theta,
                                  const std::vector<std::size_t>& base_columns, const std::vector<double>& noise,
                                  const RobotDesignOptions& options) {
  RequireValid(options);
  const std::size_t n = robot.size();
  if (noise.size() != n || static_cast<std::size_t>(theta.size()) != kSerialColumnsPerJoint * n || base_columns.empty()) {
    throw std::logic_error("DesignRobotExcitation: one noise per joint, kSerialColumnsPerJoint parameters per joint, base columns");
  }
  const double period = options.period > 0.0 ? options.period : options.duration / std::ceil(options.duration / 10.0);
  Problem p = MakeProblem(robot, theta, base_columns, noise, options, period);
  const std::size_t points = static_cast<std::size_t>(std::max(64, 16 * options.harmonics));
  const std::vector<double> grid = Grid(period, points);
  const double samples = std::floor(options.duration * options.rate) + 1.0;
  p.samples_per_grid = samples / static_cast<double>(points);
  RequireRestWithinLimits(p);
  RobotDesign design;
  design.period = period;
  const SimplexResult best = Optimise(p, grid, options.evaluations, &design.evaluations);
  // The design on the logging grid: limits checked there, shrunk if a peak
  // between the optimiser's grid points exceeds one.
  const std::vector<double> fine =
      Grid(period, static_cast<std::size_t>(std::max(2.0 * static_cast<double>(points), std::ceil(period * options.rate))));
  Candidate c = Shrunk(p, Scale(p, best.x, grid), grid);
  std::vector<double> peaks;
  for (int it = 0; it < 30 && TorqueRatio(p, c, 1.0, fine, &peaks) > 1.0; ++it) {
    for (auto& ref : c.reference) ref = ScaledReference(ref, 0.98);
  }
  Predict(p, c, fine, samples, design);
  for (std::size_t j = 0; j < n; ++j) design.joints.push_back(DesignedJoint(robot.joints[j].name, c, j, fine, peaks[j], p.limits[j]));
  return design;
}

SampledRobotTrajectory SampleRobotTrajectory(const RobotDesign& design, double rate, double duration) {
  SampledRobotTrajectory out;
  const std::size_t n = design.joints.size();
  out.position.assign(n, {});
  out.rate.assign(n, {});
  out.acceleration.assign(n, {});
  const auto count = static_cast<std::size_t>(std::floor(duration * rate + 1e-9)) + 1;
  for (std::size_t k = 0; k < count; ++k) {
    const double t = static_cast<double>(k) / rate;
    out.time.push_back(t);
    for (std::size_t j = 0; j < n; ++j) {
      const ReferenceSample3 s = design.joints[j].reference.At(t);
      out.position[j].push_back(design.joints[j].start + s.position);
      out.rate[j].push_back(s.rate);
      out.acceleration[j].push_back(s.acceleration);
    }
  }
  return out;
}

}  // namespace driveid
