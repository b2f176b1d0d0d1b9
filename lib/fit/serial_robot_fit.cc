#include "fit/serial_robot_fit.h"

#include <cmath>
#include <random>

#include <Eigen/QR>
#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"
#include "fit/adequacy.h"
#include "fit/linear_regression.h"
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
  const std::size_t n = robot.size(), samples = log.time.size();
  if (log.position.size() != n || log.torque.size() != n || (!log.rate.empty() && log.rate.size() != n)) {
    throw InputError(fmt::format("{}: the log has {} joints' columns, the robot {} joints", log.path,
                                 log.position.size(), n));
  }
  for (std::size_t j = 0; j < n; ++j) {
    const bool rate_ok = log.rate.empty() || log.rate[j].empty() || log.rate[j].size() == samples;
    if (log.position[j].size() != samples || log.torque[j].size() != samples || !rate_ok) {
      throw InputError(fmt::format("{}: joint {}'s columns differ in length from the time column", log.path,
                                   robot.joints[j].name));
    }
  }
}

}  // namespace

SerialMotion DifferentiateSerialLog(const SerialRobot& robot, const SerialRobotLog& log, double half_window) {
  CheckLog(robot, log);
  const std::size_t n = robot.size(), samples = log.time.size();
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
  const std::size_t n = robot.size(), r = base.base.size();
  std::vector<Eigen::MatrixXd> rows(n, Eigen::MatrixXd(static_cast<Eigen::Index>(m.sample.size()), static_cast<Eigen::Index>(r)));
  Eigen::MatrixXd y(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(kSerialColumnsPerJoint * n));
  for (std::size_t k = 0; k < m.sample.size(); ++k) {
    CalcSerialRegressor(robot, m.q[k], m.qd[k], m.qdd[k], y);
    for (std::size_t j = 0; j < n; ++j) {
      for (std::size_t c = 0; c < r; ++c) {
        rows[j](static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(c)) =
            y(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(base.base[c]));
      }
    }
  }
  return rows;
}

SerialJointStatistics Statistics(const std::string& joint, const std::vector<double>& measured,
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

}  // namespace

BaseParameters SerialBaseParameters(const SerialRobot& robot) {
  const auto n = static_cast<Eigen::Index>(robot.size());
  const auto columns = static_cast<Eigen::Index>(kSerialColumnsPerJoint) * n;
  const int samples = std::max(20, static_cast<int>(kStructureSamples * columns / std::max<Eigen::Index>(1, n)));
  std::mt19937 rng(kStructureSeed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  Eigen::MatrixXd w(n * samples, columns);
  for (int s = 0; s < samples; ++s) {
    Eigen::VectorXd q(n), qd(n), qdd(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      q(i) = robot.joints[static_cast<std::size_t>(i)].type == SerialJointType::kRevolute ? angle(rng) : normal(rng);
      qd(i) = normal(rng);
      qdd(i) = normal(rng);
    }
    CalcSerialRegressor(robot, q, qd, qdd, w.middleRows(s * n, n));
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
  std::size_t samples = 0;
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
void KeepMoving(const std::vector<char>& drop, Eigen::MatrixXd& x, std::vector<double>& tau, std::vector<double>& at,
                Eigen::MatrixXd& dropped_x, std::vector<double>& dropped_tau) {
  std::size_t kept = 0, count = 0;
  for (char d : drop) count += d != 0;
  dropped_x.resize(static_cast<Eigen::Index>(count), x.cols());
  dropped_tau.clear();
  for (std::size_t k = 0; k < drop.size(); ++k) {
    if (drop[k]) {
      dropped_x.row(static_cast<Eigen::Index>(dropped_tau.size())) = x.row(static_cast<Eigen::Index>(k));
      dropped_tau.push_back(tau[k]);
      continue;
    }
    x.row(static_cast<Eigen::Index>(kept)) = x.row(static_cast<Eigen::Index>(k));
    at[kept] = at[k];
    tau[kept++] = tau[k];
  }
  x.conservativeResize(static_cast<Eigen::Index>(kept), Eigen::NoChange);
  tau.resize(kept);
  at.resize(kept);
}

// Each joint's rows at its standstill are left out (AtStandstill).
Rows BuildRows(const SerialRobot& robot, const BaseParameters& base, const std::vector<SerialRobotLog>& logs,
               double half_window) {
  const std::size_t n = robot.size();
  Rows rows;
  rows.tau.resize(n);
  rows.at.resize(n);
  rows.dropped_tau.resize(n);
  for (const SerialRobotLog& log : logs) {
    const SerialMotion m = DifferentiateSerialLog(robot, log, half_window);
    std::vector<Eigen::MatrixXd> x = BaseRows(robot, base, m), dropped(n);
    for (std::size_t j = 0; j < n; ++j) {
      std::vector<double> at = m.time, t, dropped_tau;
      for (std::size_t k : m.sample) t.push_back(log.torque[j][k]);
      KeepMoving(AtStandstill(m, j), x[j], t, at, dropped[j], dropped_tau);
      rows.tau[j].push_back(std::move(t));
      rows.at[j].push_back(std::move(at));
      rows.dropped_tau[j].push_back(std::move(dropped_tau));
    }
    rows.x.push_back(std::move(x));
    rows.dropped_x.push_back(std::move(dropped));
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
      const Eigen::Map<const Eigen::VectorXd> tau(taus[j][l].data(), static_cast<Eigen::Index>(taus[j][l].size()));
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
        const double t = rows.tau[j][l][static_cast<std::size_t>(k)];
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
void AddProcessingUncertainty(const SerialRobot& robot, const BaseParameters& base, const Rows& nominal,
                              const std::vector<SerialRobotLog>& logs, const SerialRobotFitOptions& options,
                              const std::vector<double>& sigma, FitResult& fit) {
  const std::size_t r = base.base.size();
  Eigen::VectorXd theta(static_cast<Eigen::Index>(r));
  for (std::size_t c = 0; c < r; ++c) theta(static_cast<Eigen::Index>(c)) = fit.estimates[c].value;
  const auto window = [&](double half_window) { return Solve(BuildRows(robot, base, logs, half_window), r, sigma); };
  const auto timing = [&](double shift) {
    const auto torques = ShiftedTorques(nominal, logs, shift);
    return Solve(nominal, r, sigma, &torques);
  };
  struct Systematic {
    Eigen::VectorXd gradient;
    double sigma;
    std::string what;
  };
  std::vector<Systematic> errors = {
      {window(0.5 * options.half_window) - theta, 1.0 / std::sqrt(2.0), "half window halved"},
      {window(2.0 * options.half_window) - theta, 1.0 / std::sqrt(2.0), "half window doubled"},
      {0.5 * (timing(0.5) - timing(-0.5)), 1.0 / std::sqrt(3.0), "torque timing +-1/2 sample"}};
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

SerialRobotFitOutput FitSerialRobot(const SerialRobot& robot, const std::vector<SerialRobotLog>& logs,
                                    const SerialRobotFitOptions& options) {
  RequireValid(options);
  const std::size_t n = robot.size();
  SerialRobotFitOutput out;
  out.parameter_names = SerialParameterNames(robot);
  out.base = SerialBaseParameters(robot);
  const std::size_t r = out.base.base.size();
  const Rows rows = BuildRows(robot, out.base, logs, options.half_window);
  out.samples = rows.samples;
  if (out.samples * n < 2 * r) {
    throw InputError(fmt::format("{}: {} usable samples for {} base parameters: log more of the trajectory (or a "
                                 "shorter ‹window›)",
                                 logs.empty() ? std::string("the logs") : logs.front().path, out.samples, r));
  }
  const std::vector<double> sigma = JointNoise(rows, r);
  const Eigen::VectorXd first = Solve(rows, r, sigma);
  std::vector<std::string> names;
  for (std::size_t c = 0; c < r; ++c) names.push_back(out.parameter_names[out.base.base[c]]);
  LinearRegression regression(names);
  regression.Reserve(out.samples * n);
  std::vector<double> values(r);
  for (std::size_t j = 0; j < n; ++j) {
    regression.BeginChannel(robot.joints[j].name);
    for (std::size_t l = 0; l < logs.size(); ++l) {
      const Eigen::MatrixXd& x = rows.x[l][j];
      for (Eigen::Index k = 0; k < x.rows(); ++k) {
        for (std::size_t c = 0; c < r; ++c) values[c] = x(k, static_cast<Eigen::Index>(c)) / sigma[j];
        regression.AddRow(values, rows.tau[j][l][static_cast<std::size_t>(k)] / sigma[j]);
      }
    }
  }
  std::vector<FitParameter> free;
  for (std::size_t c = 0; c < r; ++c) {
    const double v = first(static_cast<Eigen::Index>(c));
    free.push_back({names[c], v, -std::numeric_limits<double>::infinity(), std::abs(v) > 0.0 ? std::abs(v) : 1.0});
  }
  out.fit = regression.FitAndRelease(free, {}, options.fit);
  // The channels' residuals were weighted by 1 / sigma_j: their rmse back in
  // the joint's unit [N m or N] (fit %, relative error and lag-1 are ratios).
  for (std::size_t j = 0; j < n && j < out.fit.channels.size(); ++j) out.fit.channels[j].rmse *= sigma[j];
  if (!out.fit.singular_values.empty() && out.fit.singular_values.back() > 0.0) {
    out.condition_number = out.fit.singular_values.front() / out.fit.singular_values.back();
  }
  AddProcessingUncertainty(robot, out.base, rows, logs, options, sigma, out.fit);
  // Each joint's statistics over every sample, standstill included: what
  // `validate` reports for the same log.
  Eigen::VectorXd fitted(static_cast<Eigen::Index>(r));
  for (std::size_t c = 0; c < r; ++c) fitted(static_cast<Eigen::Index>(c)) = out.fit.estimates[c].value;
  std::vector<std::vector<double>> measured(n), predicted(n);
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t l = 0; l < logs.size(); ++l) {
      for (const auto& [x, tau] : {std::pair{&rows.x[l][j], &rows.tau[j][l]}, std::pair{&rows.dropped_x[l][j], &rows.dropped_tau[j][l]}}) {
        const Eigen::VectorXd model = *x * fitted;
        measured[j].insert(measured[j].end(), tau->begin(), tau->end());
        predicted[j].insert(predicted[j].end(), model.data(), model.data() + model.size());
      }
    }
  }
  for (std::size_t j = 0; j < n; ++j) {
    out.joints.push_back(Statistics(robot.joints[j].name, measured[j], predicted[j]));
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
  for (std::size_t j = 0; j < robot.size(); ++j) {
    std::vector<double> measured, predicted;
    for (std::size_t k = 0; k < m.sample.size(); ++k) {
      measured.push_back(log.torque[j][m.sample[k]]);
      predicted.push_back(rows[j].row(static_cast<Eigen::Index>(k)).dot(beta));
    }
    p.joints.push_back(Statistics(robot.joints[j].name, measured, predicted));
    p.measured.push_back(std::move(measured));
    p.predicted.push_back(std::move(predicted));
  }
  return p;
}

}  // namespace driveid
