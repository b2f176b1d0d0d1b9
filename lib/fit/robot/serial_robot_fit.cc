#include "fit/robot/serial_robot_fit.h"

#include <cmath>
#include <algorithm>
#include <optional>
#include <random>
#include <tuple>

#include <Eigen/QR>
#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "fit/core/adequacy.h"
#include "fit/core/linear_regression.h"
#include "models/serial_dynamics.h"
#include "signal/local_polynomial.h"
#include "signal/resample.h"

namespace driveid {

bool SerialRobotFitOptions::IsValid(std::string* error) const {
  return OptionCheck(error).Require(half_window > 0.0 && std::isfinite(half_window), "‹window›", half_window,
                                    "half window > 0 s");
}

namespace {

// Samples of random motions per parameter column: the structure's rows
// outnumber the columns several times, so only true identities survive.
constexpr int kStructureSamples = 8;
constexpr unsigned kStructureSeed = 20260528u;
// A joint slower than this fraction of its fastest stands still (AtStandstill).
constexpr double kStandstillFraction = 0.01;

void CheckLog(const SerialRobot& robot, const SerialRobotLog& log) {
  const std::vector<std::string> names = SerialCoordinateNames(robot);
  const std::size_t n = names.size(), samples = log.time.size();
  if (log.position.size() != n || log.torque.size() != n || (!log.rate.empty() && log.rate.size() != n)) {
    throw InputError(fmt::format("{}: the log has {} joints' columns, the robot {} joints", log.path,
                                 log.position.size(), n));
  }
  for (std::size_t j = 0; j < n; ++j) {
    const bool rate_ok = log.rate.empty() || log.rate[j].empty() || log.rate[j].size() == samples;
    if (log.position[j].size() != samples || log.torque[j].size() != samples || !rate_ok) {
      throw InputError(fmt::format("{}: joint {}'s columns differ in length from the time column", log.path, names[j]));
    }
  }
}

}  // namespace

SerialMotion DifferentiateSerialLog(const SerialRobot& robot, const SerialRobotLog& log, double half_window) {
  CheckLog(robot, log);
  const std::size_t n = log.position.size(), samples = log.time.size();
  std::vector<SignalDerivatives> position(n), rate(n);
  std::vector<char> valid(samples, 1);
  for (std::size_t j = 0; j < n; ++j) {
    position[j] = EstimateDerivatives(log.time, log.position[j], half_window);
    const bool logged = !log.rate.empty() && !log.rate[j].empty();
    if (logged) rate[j] = EstimateDerivatives(log.time, log.rate[j], half_window);
    for (std::size_t k = 0; k < samples; ++k) valid[k] = valid[k] && position[j].valid[k] && (!logged || rate[j].valid[k]);
  }
  SerialMotion m;
  for (std::size_t k = 0; k < samples; ++k) {
    if (!valid[k]) continue;
    Eigen::VectorXd q(static_cast<Eigen::Index>(n)), qd = q, qdd = q;
    for (std::size_t j = 0; j < n; ++j) {
      const auto i = static_cast<Eigen::Index>(j);
      const bool logged = !log.rate.empty() && !log.rate[j].empty();
      q(i) = position[j].value[k];
      // A logged rate is the drive's own (encoder differences at its servo
      // rate): used as logged, its acceleration from its local slope.
      qd(i) = logged ? log.rate[j][k] : position[j].rate[k];
      qdd(i) = logged ? rate[j].rate[k] : position[j].acceleration[k];
    }
    m.sample.push_back(k);
    m.time.push_back(log.time[k]);
    m.q.push_back(q);
    m.qd.push_back(qd);
    m.qdd.push_back(qdd);
  }
  return m;
}

namespace {

// The base regressor's rows per joint along a motion.
std::vector<Eigen::MatrixXd> BaseRows(const SerialRobot& robot, const BaseParameters& base, const SerialMotion& m) {
  const std::size_t n = SerialCoordinates(robot).size(), r = base.base.size();
  std::vector<Eigen::MatrixXd> rows(n, Eigen::MatrixXd(static_cast<Eigen::Index>(m.sample.size()), static_cast<Eigen::Index>(r)));
  Eigen::MatrixXd y(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(kSerialColumnsPerJoint * robot.size()));
  for (std::size_t k = 0; k < m.sample.size(); ++k) {
    CalcSerialCoordinateRegressor(robot, m.q[k], m.qd[k], m.qdd[k], y);
    for (std::size_t j = 0; j < n; ++j) {
      for (std::size_t c = 0; c < r; ++c) {
        rows[j](static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(c)) =
            y(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(base.base[c]));
      }
    }
  }
  return rows;
}

}  // namespace

double SlowestSerialLogStep(const std::vector<SerialRobotLog>& logs) {
  double step = 0.0;
  for (const SerialRobotLog& log : logs) step = std::max(step, log.time.size() > 1 ? MedianStep(log.time) : 0.0);
  return step;
}

SerialJointStatistics CalcSerialJointStatistics(const std::string& joint, const std::vector<double>& measured,
                                                const std::vector<double>& predicted) {
  double e2 = 0.0, t2 = 0.0, mean = 0.0;
  for (double v : measured) mean += v / static_cast<double>(measured.size());
  double d2 = 0.0;
  for (std::size_t k = 0; k < measured.size(); ++k) {
    e2 += std::pow(measured[k] - predicted[k], 2);
    t2 += measured[k] * measured[k];
    d2 += std::pow(measured[k] - mean, 2);
  }
  SerialJointStatistics s;
  s.joint = joint;
  s.rmse = std::sqrt(e2 / static_cast<double>(std::max<std::size_t>(1, measured.size())));
  s.fit_percent = d2 > 0.0 ? 100.0 * (1.0 - std::sqrt(e2 / d2)) : 0.0;
  s.relative_error_percent = t2 > 0.0 ? 100.0 * std::sqrt(e2 / t2) : 0.0;
  return s;
}

BaseParameters SerialBaseParameters(const SerialRobot& robot) {
  // Random motions of the coordinates (mimic joints follow their leaders).
  const std::vector<std::size_t> coordinates = SerialCoordinates(robot);
  const auto n = static_cast<Eigen::Index>(coordinates.size());
  const auto columns = static_cast<Eigen::Index>(kSerialColumnsPerJoint * robot.size());
  const int samples = std::max(20, static_cast<int>(kStructureSamples * columns / std::max<Eigen::Index>(1, n)));
  std::mt19937 rng(kStructureSeed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  Eigen::MatrixXd w(n * samples, columns);
  for (int s = 0; s < samples; ++s) {
    Eigen::VectorXd q(n), qd(n), qdd(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const SerialJoint& joint = robot.joints[coordinates[static_cast<std::size_t>(i)]];
      q(i) = joint.type == SerialJointType::kRevolute ? angle(rng) : normal(rng);
      qd(i) = normal(rng);
      qdd(i) = normal(rng);
    }
    CalcSerialCoordinateRegressor(robot, q, qd, qdd, w.middleRows(s * n, n));
  }
  return FindBaseParameters(w, SerialParameterNames(robot));
}

namespace {

// The base regressor's rows and the torques of every log, joint by joint.
struct Rows {
  std::vector<std::vector<Eigen::MatrixXd>> x;          // [log][joint]: samples x r
  std::vector<std::vector<std::vector<double>>> tau;    // [joint][log][sample]
  std::vector<std::vector<std::vector<double>>> at;     // [joint][log][sample]: its time [s]
  // The rows left out at standstill, for the statistics over every sample.
  std::vector<std::vector<Eigen::MatrixXd>> dropped_x;        // [log][joint]
  std::vector<std::vector<std::vector<double>>> dropped_tau;  // [joint][log]
  // The held base parameters' torque (Selection), at the kept and dropped rows.
  std::vector<std::vector<std::vector<double>>> known, dropped_known;  // [joint][log][sample]
  std::size_t samples = 0;
};

// The base parameters estimated (indices into base) and the values of the
// others (zero at the free ones), whose torque is known.
struct Selection {
  std::vector<std::size_t> free;
  Eigen::VectorXd held;
  bool all() const { return free.size() == static_cast<std::size_t>(held.size()); }
};

// Joint j's samples at standstill: slower than kStandstillFraction of its
// fastest. There a drive sticks — static friction holds any torque up to
// its breakaway, a position loop dithers about a stop, a harmonic drive's
// friction passes smoothly through zero — which the model's tau_c sgn q'
// cannot describe; on the closed-loop arm of the tests such rows biased
// viscous friction by +10 % and Coulomb by -7 % (docs/models.md#serial-robot-identification).
// The joint's rows there are left out (its torque row only).
std::vector<char> AtStandstill(const SerialMotion& m, std::size_t j) {
  const auto i = static_cast<Eigen::Index>(j);
  double fastest = 0.0;
  for (const Eigen::VectorXd& v : m.qd) fastest = std::max(fastest, std::abs(v(i)));
  std::vector<char> slow(m.sample.size(), 0);
  for (std::size_t k = 0; k < slow.size(); ++k) slow[k] = std::abs(m.qd[k](i)) < kStandstillFraction * fastest;
  return slow;
}

// Moves the rows, torques and times where `drop` is set to `dropped_x`
// and `dropped_tau`, keeping the others in order.
struct JointRows {
  Eigen::MatrixXd x;
  std::vector<double> tau, at, known;
};
void KeepMoving(const std::vector<char>& drop, JointRows& rows, JointRows& dropped) {
  std::size_t kept = 0, count = 0;
  for (char d : drop) count += d != 0;
  dropped.x.resize(static_cast<Eigen::Index>(count), rows.x.cols());
  for (std::size_t k = 0; k < drop.size(); ++k) {
    if (drop[k]) {
      dropped.x.row(static_cast<Eigen::Index>(dropped.tau.size())) = rows.x.row(static_cast<Eigen::Index>(k));
      dropped.tau.push_back(rows.tau[k]);
      dropped.known.push_back(rows.known[k]);
      continue;
    }
    rows.x.row(static_cast<Eigen::Index>(kept)) = rows.x.row(static_cast<Eigen::Index>(k));
    rows.at[kept] = rows.at[k];
    rows.known[kept] = rows.known[k];
    rows.tau[kept++] = rows.tau[k];
  }
  rows.x.conservativeResize(static_cast<Eigen::Index>(kept), Eigen::NoChange);
  rows.tau.resize(kept);
  rows.at.resize(kept);
  rows.known.resize(kept);
}

// A joint's rows on the free base parameters, the held ones' torque known.
JointRows SplitHeld(Eigen::MatrixXd&& full, const Selection& selection) {
  JointRows out;
  if (selection.all()) {  // nothing held: the rows as they are (moved, not copied: 20 MB a joint at 5 kHz)
    out.known.assign(static_cast<std::size_t>(full.rows()), 0.0);
    out.x = std::move(full);
    return out;
  }
  const Eigen::VectorXd known = full * selection.held;
  out.known.assign(known.data(), known.data() + known.size());
  out.x.resize(full.rows(), static_cast<Eigen::Index>(selection.free.size()));
  for (std::size_t c = 0; c < selection.free.size(); ++c) {
    out.x.col(static_cast<Eigen::Index>(c)) = full.col(static_cast<Eigen::Index>(selection.free[c]));
  }
  return out;
}

// Each joint's rows at its standstill are left out (AtStandstill).
Rows BuildRows(const SerialRobot& robot, const BaseParameters& base, const Selection& selection,
               const std::vector<SerialRobotLog>& logs, double half_window) {
  const std::size_t n = SerialCoordinates(robot).size();
  Rows rows;
  for (auto* v : {&rows.tau, &rows.at, &rows.dropped_tau, &rows.known, &rows.dropped_known}) v->resize(n);
  for (const SerialRobotLog& log : logs) {
    const SerialMotion m = DifferentiateSerialLog(robot, log, half_window);
    std::vector<Eigen::MatrixXd> full = BaseRows(robot, base, m);
    std::vector<Eigen::MatrixXd> x(n), dropped_x(n);
    for (std::size_t j = 0; j < n; ++j) {
      JointRows kept = SplitHeld(std::move(full[j]), selection), dropped;
      kept.at = m.time;
      for (std::size_t k : m.sample) kept.tau.push_back(log.torque[j][k]);
      KeepMoving(AtStandstill(m, j), kept, dropped);
      x[j] = std::move(kept.x);
      dropped_x[j] = std::move(dropped.x);
      rows.tau[j].push_back(std::move(kept.tau));
      rows.at[j].push_back(std::move(kept.at));
      rows.known[j].push_back(std::move(kept.known));
      rows.dropped_tau[j].push_back(std::move(dropped.tau));
      rows.dropped_known[j].push_back(std::move(dropped.known));
    }
    rows.x.push_back(std::move(x));
    rows.dropped_x.push_back(std::move(dropped_x));
    rows.samples += m.sample.size();
  }
  return rows;
}

// Least squares on the rows, each joint's weighted by 1 / sigma[j], by the
// normal equations on columns scaled to unit diagonal: the rows are not
// stacked (a 5 kHz log of a six-joint arm has ~10^5 rows per joint) and
// the base regressor is well conditioned by construction (its columns are
// independent on random motions), so the squared condition number costs
// no digits that matter. A direction the logs do not excite is caught by
// the fit core's identifiability check afterwards.
// `torques`: in place of rows.tau (the same rows read at other times).
Eigen::VectorXd Solve(const Rows& rows, std::size_t r, const std::vector<double>& sigma,
                      const std::vector<std::vector<std::vector<double>>>* torques = nullptr) {
  const auto& taus = torques != nullptr ? *torques : rows.tau;
  const auto p = static_cast<Eigen::Index>(r);
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(p, p);
  Eigen::VectorXd right = Eigen::VectorXd::Zero(p);
  for (std::size_t j = 0; j < rows.tau.size(); ++j) {
    const double w = 1.0 / (sigma[j] * sigma[j]);
    for (std::size_t l = 0; l < rows.x.size(); ++l) {
      const Eigen::MatrixXd& x = rows.x[l][j];
      // A log a window leaves without rows has an empty block (0 x 0: Eigen's
      // products of it divide by its size).
      if (x.rows() == 0 || x.cols() != p) continue;
      const auto size = static_cast<Eigen::Index>(taus[j][l].size());
      const Eigen::VectorXd tau = Eigen::Map<const Eigen::VectorXd>(taus[j][l].data(), size) -
                                  Eigen::Map<const Eigen::VectorXd>(rows.known[j][l].data(), size);
      normal.selfadjointView<Eigen::Lower>().rankUpdate(x.transpose(), w);
      right += w * (x.transpose() * tau);
    }
  }
  Eigen::VectorXd scale(p);
  for (Eigen::Index c = 0; c < p; ++c) {
    const double d = normal(c, c);
    scale(c) = d > 0.0 ? 1.0 / std::sqrt(d) : 1.0;
  }
  const Eigen::MatrixXd full = normal.selfadjointView<Eigen::Lower>();
  const Eigen::MatrixXd scaled = scale.asDiagonal() * full * scale.asDiagonal();
  return scale.asDiagonal() * scaled.ldlt().solve(scale.asDiagonal() * right);
}

// Each joint's residual RMS of an unweighted solve: its weight's std.
std::vector<double> JointNoise(const Rows& rows, std::size_t r) {
  const std::size_t n = rows.tau.size();
  const Eigen::VectorXd first = Solve(rows, r, std::vector<double>(n, 1.0));
  std::vector<double> sigma(n);
  for (std::size_t j = 0; j < n; ++j) {
    double e2 = 0.0, t2 = 0.0;
    std::size_t used = 0;
    for (std::size_t l = 0; l < rows.x.size(); ++l) {
      const Eigen::VectorXd model = rows.x[l][j] * first;
      used += static_cast<std::size_t>(model.size());
      for (Eigen::Index k = 0; k < model.size(); ++k) {
        const double t = rows.tau[j][l][static_cast<std::size_t>(k)] - rows.known[j][l][static_cast<std::size_t>(k)];
        e2 += (t - model(k)) * (t - model(k));
        t2 += t * t;
      }
    }
    const double count = static_cast<double>(std::max<std::size_t>(1, used));
    sigma[j] = std::max(std::sqrt(e2 / count), 1e-9 * std::sqrt(t2 / count) + 1e-300);
  }
  return sigma;
}

// The rows' torques read `shift` sample periods later (the torque's timing
// is known to within a sample: sampled at the stamp, or held since it).
std::vector<std::vector<std::vector<double>>> ShiftedTorques(const Rows& rows, const std::vector<SerialRobotLog>& logs,
                                                              double shift) {
  std::vector<std::vector<std::vector<double>>> out(rows.at.size());
  for (std::size_t l = 0; l < logs.size(); ++l) {
    const double step = shift * MedianStep(logs[l].time);
    for (std::size_t j = 0; j < rows.at.size(); ++j) {
      std::vector<double> at = rows.at[j][l];
      for (double& t : at) t += step;
      out[j].push_back(InterpolateLinear(logs[l].time, logs[l].torque[j], at));
    }
  }
  return out;
}

// The processing's share of the error (docs/models.md#serial-robot-identification):
// the estimates again with the differentiator's half window halved and
// doubled (two candidates, each a systematic error of sigma 1/sqrt 2) and
// with the torque read half a sample earlier and later (a timing known to
// within a sample: uniform, std 1/sqrt 3 of the half-sample response).
// Added where some estimate moves by more than its std.
void AddProcessingUncertainty(const SerialRobot& robot, const BaseParameters& base, const Selection& selection,
                              const Rows& nominal, const std::vector<SerialRobotLog>& logs,
                              const SerialRobotFitOptions& options, const std::vector<double>& sigma, FitResult& fit) {
  const std::size_t r = selection.free.size();
  Eigen::VectorXd theta(static_cast<Eigen::Index>(r));
  for (std::size_t c = 0; c < r; ++c) theta(static_cast<Eigen::Index>(c)) = fit.estimates[c].value;
  // A refit at another half window: none where that window leaves a joint
  // without rows (a short window halved at a low rate; a long one doubled on
  // short logs) or the solve is not finite.
  const auto window = [&](double half_window) -> std::optional<Eigen::VectorXd> {
    const Rows rows = BuildRows(robot, base, selection, logs, half_window);
    for (std::size_t j = 0; j < rows.tau.size(); ++j) {
      std::size_t count = 0;
      for (const auto& x : rows.x) count += static_cast<std::size_t>(x[j].rows());
      if (count == 0) return std::nullopt;
    }
    const Eigen::VectorXd solved = Solve(rows, r, sigma);
    if (!solved.allFinite()) return std::nullopt;
    return solved;
  };
  const auto timing = [&](double shift) {
    const auto torques = ShiftedTorques(nominal, logs, shift);
    return Solve(nominal, r, sigma, &torques);
  };
  struct Systematic {
    Eigen::VectorXd gradient;
    double sigma;
    std::string what;
  };
  std::vector<Systematic> errors;
  std::vector<std::string> unassessed;
  for (const auto& [factor, what] : {std::pair{0.5, "half window halved"}, std::pair{2.0, "half window doubled"}}) {
    const std::optional<Eigen::VectorXd> moved = window(factor * options.half_window);
    if (moved) errors.push_back({*moved - theta, 1.0 / std::sqrt(2.0), what});
    else unassessed.push_back(fmt::format("{} ({:.3g} s)", what, factor * options.half_window));
  }
  errors.push_back({0.5 * (timing(0.5) - timing(-0.5)), 1.0 / std::sqrt(3.0), "torque timing +-1/2 sample"});
  if (!unassessed.empty()) {
    fit.warnings.push_back(fmt::format(
        "processing: the differentiator's {} leaves a joint without samples, so how the estimates move with the "
        "window is not in their intervals; a window of several samples at the log's rate (‹window›) lets it be "
        "assessed",
        fmt::join(unassessed, " and ")));
  }
  bool moves = false;
  for (const Systematic& e : errors) {
    for (std::size_t c = 0; c < r; ++c) moves = moves || std::abs(e.gradient(static_cast<Eigen::Index>(c))) > fit.estimates[c].standard_error;
  }
  if (!moves) return;
  const std::vector<ParameterEstimate> before = fit.estimates;
  for (const Systematic& e : errors) {
    AddSystematicCovariance(fit, std::vector<double>(e.gradient.data(), e.gradient.data() + e.gradient.size()), e.sigma);
  }
  std::vector<std::string> widened;
  for (std::size_t c = 0; c < r; ++c) {
    const double factor = before[c].standard_error > 0.0 ? fit.estimates[c].standard_error / before[c].standard_error : 1.0;
    if (factor > 1.05) widened.push_back(fmt::format("{} x{:.2f}", fit.estimates[c].name, factor));
  }
  fit.notes.push_back(fmt::format(
      "processing: the estimates move with the differentiator's half window ({:.3g} s halved, doubled) and the torque's "
      "timing (half a sample either way) by more than their std; that spread is in the covariance and the intervals "
      "(std {})",
      options.half_window, widened.empty() ? "barely changed" : fmt::format("{}", fmt::join(widened, ", "))));
}

}  // namespace

std::vector<std::size_t> SelectSerialBaseParameters(const BaseParameters& base,
                                                    const std::vector<std::string>& parameter_names,
                                                    const std::vector<std::string>& names) {
  std::vector<char> chosen(base.base.size(), names.empty() ? 1 : 0);
  for (const std::string& name : names) {
    bool found = false;
    for (std::size_t k = 0; k < base.base.size(); ++k) {
      const bool drive = base.base[k] % kSerialColumnsPerJoint >= kInertialParameters;
      if (parameter_names[base.base[k]] == name || (name == "drives" && drive) || (name == "bodies" && !drive)) {
        chosen[k] = 1;
        found = true;
      }
    }
    if (found) continue;
    for (std::size_t k = 0; k < base.combination.size(); ++k) {
      for (const auto& [column, c] : base.combination[k]) {
        if (parameter_names[column] == name) {
          throw OptionError(fmt::format("‹free›: '{}' is not a base parameter itself but part of '{}': name that "
                                        "one (docs/models.md#serial-robot-identification)",
                                        name, base.names[k]));
        }
      }
    }
    throw OptionError(fmt::format("‹free›: '{}' is no base parameter of this robot: give a base parameter's lead "
                                  "(the first name of each in the summary), 'bodies' or 'drives'",
                                  name));
  }
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    if (chosen[k]) out.push_back(k);
  }
  return out;
}

std::vector<double> SerialRobotFitOutput::BaseValues() const {
  std::vector<double> values = held;
  for (std::size_t c = 0; c < free.size() && c < fit.estimates.size(); ++c) values[free[c]] = fit.estimates[c].value;
  return values;
}

namespace {

// The free base parameters and the held ones' prior values (beta = R theta_prior).
Selection SelectFree(const SerialRobot& robot, const SerialRobotFitOptions& options, const SerialRobotFitOutput& out) {
  if (!options.prior_drives.empty() && options.prior_drives.size() != robot.size()) {
    throw std::logic_error("FitSerialRobot: one prior drive per joint");
  }
  Selection selection;
  selection.free = SelectSerialBaseParameters(out.base, out.parameter_names, options.free);
  const Eigen::VectorXd prior = out.base.regroup * SerialParameterVector(robot, options.prior_drives);
  selection.held = prior;
  for (std::size_t k : selection.free) selection.held(static_cast<Eigen::Index>(k)) = 0.0;
  return selection;
}

// Rethrows the fit core's refusal of base parameters the logs do not
// determine with what to do about it.
[[noreturn]] void RefuseUnexcited(const IdentificationError& e) {
  throw IdentificationError(fmt::format("{}; to hold what the trajectory cannot excite at the URDF's values, list the "
                                        "others in ‹free›, or design a trajectory that excites them (design robot)",
                                        e.what()),
                            e.parameters());
}

// The logs leave too few samples: InputError with the advice that is right
// (a window of at least 2.5 steps where the window, not the logs, is short).
[[noreturn]] void RefuseTooFewSamples(const std::vector<SerialRobotLog>& logs, const SerialRobotFitOptions& options,
                                      std::size_t samples, std::size_t r) {
  // The differentiator needs 2 samples on each side of its centre
  // (signal/local_polynomial.h): a half window shorter than 2 steps of the
  // log leaves no sample, whatever its length.
  const double step = SlowestSerialLogStep(logs);
  const bool short_window = step > 0.0 && options.half_window < 2.0 * step;
  throw InputError(fmt::format(
      "{}: {} usable samples for {} base parameters: {}",
      logs.empty() ? std::string("the logs") : logs.front().path, samples, r,
      short_window ? fmt::format("the differentiator's half window ‹window› {:.3g} s spans fewer than 2 samples on "
                                 "each side at this log's step of {:.3g} s; give at least {:.2g} s",
                                 options.half_window, step, 2.5 * step)
                   : std::string("log more of the trajectory, or a shorter ‹window›")));
}

// Notes of the base parameters held at the prior, and of the drive terms
// held with a link's inertia inside them.
void NoteHeldParameters(SerialRobotFitOutput& out) {
  std::vector<std::string> held;
  for (std::size_t k = 0; k < out.held.size(); ++k) {
    if (!std::isnan(out.held[k])) held.push_back(out.parameter_names[out.base.base[k]]);
  }
  out.fit.notes.push_back(fmt::format("held at the prior (the URDF's inertials and <dynamics>), not estimated: {}; "
                                      "the intervals take them as exact",
                                      fmt::join(held, ", ")));
  // A drive term inside a held base parameter led by a body's inertia
  // (a base joint's armature beside its link's Izz) is held with it: named,
  // as `--free drives` does not fit it.
  std::vector<std::string> held_drives;
  for (std::size_t k = 0; k < out.held.size(); ++k) {
    if (std::isnan(out.held[k])) continue;
    for (const auto& [column, coefficient] : out.base.combination[k]) {
      if (column % kSerialColumnsPerJoint >= kInertialParameters && column != out.base.base[k]) {
        held_drives.push_back(out.parameter_names[column]);
      }
    }
  }
  if (!held_drives.empty()) {
    out.fit.notes.push_back(fmt::format(
        "held with a body's inertia, not fitted: {} (each lies in a base parameter that a link's inertia leads, "
        "which the free set leaves out; the logs determine only the sum: free that base parameter, e.g. ‹free› "
        "drives,bodies, to fit it)",
        fmt::join(held_drives, ", ")));
  }
}

}  // namespace

SerialRobotFitOutput FitSerialRobot(const SerialRobot& robot, const std::vector<SerialRobotLog>& logs,
                                    const SerialRobotFitOptions& options) {
  RequireValid(options);
  const std::vector<std::string> joint_names = SerialCoordinateNames(robot);
  const std::size_t n = joint_names.size();
  SerialRobotFitOutput out;
  out.parameter_names = SerialParameterNames(robot);
  out.base = SerialBaseParameters(robot);
  const Selection selection = SelectFree(robot, options, out);
  out.free = selection.free;
  out.held.assign(out.base.base.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < out.held.size(); ++k) {
    if (std::find(out.free.begin(), out.free.end(), k) == out.free.end()) out.held[k] = selection.held(static_cast<Eigen::Index>(k));
  }
  const std::size_t r = selection.free.size();
  const Rows rows = BuildRows(robot, out.base, selection, logs, options.half_window);
  out.samples = rows.samples;
  if (out.samples * n < 2 * r) RefuseTooFewSamples(logs, options, out.samples, r);
  const std::vector<double> sigma = JointNoise(rows, r);
  const Eigen::VectorXd first = Solve(rows, r, sigma);
  std::vector<std::string> names;
  for (std::size_t k : selection.free) names.push_back(out.parameter_names[out.base.base[k]]);
  LinearRegression regression(names);
  regression.Reserve(out.samples * n);
  std::vector<double> values(r);
  for (std::size_t j = 0; j < n; ++j) {
    regression.BeginChannel(joint_names[j]);
    for (std::size_t l = 0; l < logs.size(); ++l) {
      const Eigen::MatrixXd& x = rows.x[l][j];
      for (Eigen::Index k = 0; k < x.rows(); ++k) {
        for (std::size_t c = 0; c < r; ++c) values[c] = x(k, static_cast<Eigen::Index>(c)) / sigma[j];
        const auto row = static_cast<std::size_t>(k);
        regression.AddRow(values, rows.tau[j][l][row] / sigma[j], rows.known[j][l][row] / sigma[j]);
      }
    }
  }
  std::vector<FitParameter> free;
  for (std::size_t c = 0; c < r; ++c) {
    const double v = first(static_cast<Eigen::Index>(c));
    free.push_back({names[c], v, -std::numeric_limits<double>::infinity(), std::abs(v) > 0.0 ? std::abs(v) : 1.0});
  }
  try {
    out.fit = regression.FitAndRelease(free, {}, options.fit);
  } catch (const IdentificationError& e) {
    RefuseUnexcited(e);
  }
  // The channels' residuals were weighted by 1 / sigma_j: their rmse back in
  // the joint's unit [N m or N] (fit %, relative error and lag-1 are ratios).
  for (std::size_t j = 0; j < n && j < out.fit.channels.size(); ++j) out.fit.channels[j].rmse *= sigma[j];
  if (!out.fit.singular_values.empty() && out.fit.singular_values.back() > 0.0) {
    out.condition_number = out.fit.singular_values.front() / out.fit.singular_values.back();
  }
  AddProcessingUncertainty(robot, out.base, selection, rows, logs, options, sigma, out.fit);
  if (!selection.all()) NoteHeldParameters(out);
  // Each joint's statistics over every sample, standstill included: what
  // `validate` reports for the same log.
  Eigen::VectorXd fitted(static_cast<Eigen::Index>(r));
  for (std::size_t c = 0; c < r; ++c) fitted(static_cast<Eigen::Index>(c)) = out.fit.estimates[c].value;
  std::vector<std::vector<double>> measured(n), predicted(n);
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t l = 0; l < logs.size(); ++l) {
      for (const auto& [x, tau, known] : {std::tuple{&rows.x[l][j], &rows.tau[j][l], &rows.known[j][l]},
                                          std::tuple{&rows.dropped_x[l][j], &rows.dropped_tau[j][l], &rows.dropped_known[j][l]}}) {
        if (x->rows() == 0) continue;  // a log without rows (an empty block)
        const Eigen::VectorXd model = *x * fitted;
        measured[j].insert(measured[j].end(), tau->begin(), tau->end());
        for (Eigen::Index k = 0; k < model.size(); ++k) predicted[j].push_back(model(k) + (*known)[static_cast<std::size_t>(k)]);
      }
    }
  }
  for (std::size_t j = 0; j < n; ++j) {
    out.joints.push_back(CalcSerialJointStatistics(joint_names[j], measured[j], predicted[j]));
    out.joints.back().weight_std = sigma[j];
  }
  return out;
}

SerialPrediction PredictSerialRobot(const SerialRobot& robot, const BaseParameters& base,
                                    const std::vector<double>& values, const SerialRobotLog& log, double half_window) {
  if (values.size() != base.base.size()) throw std::logic_error("PredictSerialRobot: one value per base parameter");
  const SerialMotion m = DifferentiateSerialLog(robot, log, half_window);
  const std::vector<Eigen::MatrixXd> rows = BaseRows(robot, base, m);
  const Eigen::Map<const Eigen::VectorXd> beta(values.data(), static_cast<Eigen::Index>(values.size()));
  SerialPrediction p;
  p.time = m.time;
  const std::vector<std::string> names = SerialCoordinateNames(robot);
  for (std::size_t j = 0; j < names.size(); ++j) {
    std::vector<double> measured, predicted;
    for (std::size_t k = 0; k < m.sample.size(); ++k) {
      measured.push_back(log.torque[j][m.sample[k]]);
      predicted.push_back(rows[j].row(static_cast<Eigen::Index>(k)).dot(beta));
    }
    p.joints.push_back(CalcSerialJointStatistics(names[j], measured, predicted));
    p.measured.push_back(std::move(measured));
    p.predicted.push_back(std::move(predicted));
  }
  return p;
}

}  // namespace driveid
