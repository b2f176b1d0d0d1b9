// Axis IDIM-LS (docs/models.md#axis): recovery from synthetic logs, constant-rate logs
// identify friction only, the zero-phase filter has no lag.
#include "fit/axis/axis_fit.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <string>

#include <catch2/catch.hpp>

#include "core/errors.h"
#include "signal/butterworth.h"
#include "sim/axis_experiment.h"
#include "workflow/axis_feedforward.h"
#include "support/axis_values.h"

using namespace driveid;
using driveid::testing::AxisValue;

namespace {
const AxisParameters kTruth{0.05, 0.2, 1.0, 0.3};
}

TEST_CASE("zero-phase Butterworth: unit DC gain, no lag, -6 dB at the cutoff") {
  std::vector<double> x(4000), slow(4000), fast(4000);
  for (int k = 0; k < 4000; ++k) {
    x[static_cast<std::size_t>(k)] = 2.0;
    slow[static_cast<std::size_t>(k)] = std::sin(2 * M_PI * 1.0 * k / 1000.0);
    fast[static_cast<std::size_t>(k)] = std::sin(2 * M_PI * 25.0 * k / 1000.0);
  }
  const auto dc = ZeroPhaseLowPass(x, 25.0, 1000.0);
  CHECK(dc[2000] == Approx(2.0));
  const auto s = ZeroPhaseLowPass(slow, 25.0, 1000.0);
  CHECK(s[2000 + 250] == Approx(slow[2000 + 250]).margin(1e-3));  // peak of the 1 Hz sine: no lag
  const auto f = ZeroPhaseLowPass(fast, 25.0, 1000.0);
  double peak = 0.0;
  for (int k = 1000; k < 3000; ++k) peak = std::max(peak, std::abs(f[static_cast<std::size_t>(k)]));
  CHECK(peak == Approx(0.5).epsilon(0.02));  // |H|^2 of a second-order Butterworth at the cutoff
  CHECK(ConstantRate({0, 0.001, 0.002, 0.003}) == Approx(1000.0));
  CHECK(ConstantRate({0, 0.001, 0.0025, 0.003}) == 0.0);
}

// filtfilt by its definition: pad by odd reflection, filter forward from the
// steady state of the first value, reverse, filter again, reverse, cut.
static std::vector<double> ReferenceZeroPhase(const std::vector<double>& signal, double cutoff, double rate) {
  const std::size_t n = signal.size();
  const double k = std::tan(M_PI * cutoff / rate), q = std::sqrt(0.5);
  const double norm = 1.0 / (1.0 + k / q + k * k);
  const double b0 = k * k * norm, b1 = 2.0 * b0, b2 = b0;
  const double a1 = 2.0 * (k * k - 1.0) * norm, a2 = (1.0 - k / q + k * k) * norm;
  const std::size_t pad = std::min<std::size_t>(n - 1, static_cast<std::size_t>(std::ceil(3.0 * rate / cutoff)) + 1);
  std::vector<double> x;
  for (std::size_t i = pad; i >= 1; --i) x.push_back(2.0 * signal.front() - signal[i]);
  x.insert(x.end(), signal.begin(), signal.end());
  for (std::size_t i = 1; i <= pad; ++i) x.push_back(2.0 * signal.back() - signal[n - 1 - i]);
  for (int pass = 0; pass < 2; ++pass) {
    double z1 = x.front() * (1.0 - b0), z2 = x.front() * (b2 - a2);
    for (double& v : x) {
      const double in = v, out = b0 * in + z1;
      z1 = b1 * in - a1 * out + z2;
      z2 = b2 * in - a2 * out;
      v = out;
    }
    std::reverse(x.begin(), x.end());
  }
  return {x.begin() + static_cast<std::ptrdiff_t>(pad), x.begin() + static_cast<std::ptrdiff_t>(pad + n)};
}

TEST_CASE("zero-phase Butterworth in place: the padded definition, bit for bit, short and long") {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (std::size_t n : {2u, 3u, 10u, 130u, 5000u}) {
    std::vector<double> x(n);
    for (std::size_t k = 0; k < n; ++k) x[k] = std::sin(0.01 * static_cast<double>(k)) + 0.1 * noise(rng);
    const std::vector<double> expected = ReferenceZeroPhase(x, 25.0, 1000.0);
    ZeroPhaseLowPassInPlace(x, 25.0, 1000.0);
    REQUIRE(x.size() == n);
    for (std::size_t k = 0; k < n; ++k) CHECK(x[k] == expected[k]);
  }
}

TEST_CASE("axis: multisine logs recover the truth within 1 % with the defaults") {
  for (unsigned seed : {1u, 2u, 3u}) {
    AxisExperiment e;
    e.noise = 0.05;
    e.duration = 25.0;
    e.seed = seed;
    const AxisFitOutput out = FitAxis({SimulateAxisExperiment(kTruth, e)}, AxisSection{0.1, 0.5, 2.0, 0.0, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}}, {});
    CHECK(out.params.inertia == Approx(kTruth.inertia).epsilon(0.01));
    CHECK(out.params.viscous == Approx(kTruth.viscous).epsilon(0.01));
    CHECK(out.params.coulomb == Approx(kTruth.coulomb).epsilon(0.01));
    CHECK(out.params.offset == Approx(kTruth.offset).epsilon(0.01));
    CHECK(out.relative_error_percent < 3.0);
  }
}

TEST_CASE("axis: irregular sampling is detected and handled without assuming a rate") {
  AxisExperiment e;
  e.noise = 0.05;
  e.duration = 25.0;
  AxisLog log = SimulateAxisExperiment(kTruth, e);
  // Drop every 7th sample: the rate is no longer constant.
  AxisLog irregular{log.path, {}, {}, {}, {}};
  for (std::size_t k = 0; k < log.time.size(); ++k) {
    if (k % 7 == 3) continue;
    irregular.time.push_back(log.time[k]);
    irregular.position.push_back(log.position[k]);
    irregular.force.push_back(log.force[k]);
  }
  const AxisFitOutput out = FitAxis({irregular}, AxisSection{0.1, 0.5, 2.0, 0.0, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}}, {});
  CHECK(out.method.find("irregular") != std::string::npos);
  CHECK(out.params.inertia == Approx(kTruth.inertia).epsilon(0.02));
  CHECK(out.params.coulomb == Approx(kTruth.coulomb).epsilon(0.02));
}

TEST_CASE("axis: constant-rate logs identify friction only, a free inertia is refused by name") {
  std::vector<AxisLog> logs;
  for (double speed : {0.5, -0.5, 2.0, -2.0}) {
    AxisExperiment e;
    e.profile = "constant";
    e.speed = speed;
    e.noise = 0.05;
    e.duration = 5.0;
    logs.push_back(SimulateAxisExperiment(kTruth, e));
  }
  AxisSection start{std::nullopt, 0.5, 2.0, 0.0, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}};  // inertia not given
  try {
    FitAxis(logs, start, {});
    FAIL("fitted an inertia from constant-rate logs");
  } catch (const IdentificationError& e) {
    CHECK(std::string(e.what()).find("inertia") != std::string::npos);
  }
  AxisFitOptions friction;
  friction.free = {"viscous", "coulomb", "offset"};
  const AxisFitOutput out = FitAxis(logs, start, friction);
  CHECK(out.params.viscous == Approx(kTruth.viscous).epsilon(0.01));
  CHECK(out.params.coulomb == Approx(kTruth.coulomb).epsilon(0.01));
  CHECK(out.params.offset == Approx(kTruth.offset).epsilon(0.01));
}

namespace {

// The tests' own generator (not lib/sim): a joint swinging about the
// horizontal, q = s (0.6 sin(2 pi 0.5 t) + 0.2 sin(2 pi 1.7 t)) (s = `scale`),
// 1 kHz for 20 s, tau = torque(t, q, q', q'') + white noise 0.02.
AxisLog SwingWith(const std::function<double(double, double, double, double)>& torque, unsigned seed,
                  double scale = 1.0) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, 0.02);
  AxisLog log;
  log.path = "swing.csv";
  for (int k = 0; k <= 20000; ++k) {
    const double t = k / 1000.0, w1 = 2 * M_PI * 0.5, w2 = 2 * M_PI * 1.7;
    const double q = scale * (0.6 * std::sin(w1 * t) + 0.2 * std::sin(w2 * t));
    const double qd = scale * (0.6 * w1 * std::cos(w1 * t) + 0.2 * w2 * std::cos(w2 * t));
    const double qdd = -scale * (0.6 * w1 * w1 * std::sin(w1 * t) + 0.2 * w2 * w2 * std::sin(w2 * t));
    log.time.push_back(t);
    log.position.push_back(q);
    log.force.push_back(torque(t, q, qd, qdd) + noise(random));
  }
  return log;
}

// The adequacy checks' swing: J 0.05, b, tau_c 0.3, tau_0 0.1, gravity
// g_c cos q + g_s sin q and a drift of drift_rate t.
AxisLog SwingLog(double viscous, double gravity_cos, double gravity_sin, double drift_rate, unsigned seed) {
  return SwingWith(
      [&](double t, double q, double qd, double qdd) {
        return 0.05 * qdd + viscous * qd + 0.3 * ((qd > 0) - (qd < 0)) + 0.1 + gravity_cos * std::cos(q) +
               gravity_sin * std::sin(q) + drift_rate * t;
      },
      seed);
}

bool HasWarning(const FitResult& fit, const std::string& start) {
  for (const auto& w : fit.warnings) {
    if (w.rfind(start, 0) == 0) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("axis adequacy: missing gravity is named, the gravity terms recover it and silence the warning") {
  const AxisLog log = SwingLog(0.2, -3.0, 0.8, 0.0, 11);
  const AxisFitOutput without = FitAxis({log}, AxisSection{}, {});
  CHECK(HasWarning(without.fit, "gravity missing?"));
  AxisFitOptions with_gravity;
  with_gravity.free = {"inertia", "viscous", "coulomb", "offset", "gravity_cos", "gravity_sin"};
  const AxisFitOutput with = FitAxis({log}, AxisSection{}, with_gravity);
  CHECK_FALSE(HasWarning(with.fit, "gravity missing?"));
  // Offset and gravity_cos are close to collinear for |q| < 0.8: checked
  // through their sum at q = 0 and the shape terms.
  CHECK(with.params.gravity_sin == Approx(0.8).epsilon(0.05));
  CHECK(with.params.offset + with.params.gravity_cos == Approx(0.1 - 3.0).epsilon(0.02));
  CHECK(with.params.inertia == Approx(0.05).epsilon(0.03));
  CHECK(with.params.viscous == Approx(0.2).epsilon(0.03));
  CHECK(with.fit.warnings.empty());
}

TEST_CASE("axis adequacy: drift within a log and logs that disagree draw warnings; consistent logs do not") {
  const AxisFitOutput drifting = FitAxis({SwingLog(0.2, 0.0, 0.0, 0.02, 12)}, AxisSection{}, {});
  CHECK(HasWarning(drifting.fit, "drift"));
  const AxisFitOutput same = FitAxis({SwingLog(0.2, 0.0, 0.0, 0.0, 13), SwingLog(0.2, 0.0, 0.0, 0.0, 14)},
                                     AxisSection{}, {});
  CHECK(same.fit.warnings.empty());
  REQUIRE(same.fit.per_log.size() == 2);
  const AxisFitOutput differ = FitAxis({SwingLog(0.2, 0.0, 0.0, 0.0, 15), SwingLog(0.3, 0.0, 0.0, 0.0, 16)},
                                       AxisSection{}, {});
  CHECK(HasWarning(differ.fit, "logs disagree: viscous"));
  bool viscous_tested = false;
  for (const auto& t : differ.fit.heterogeneity) {
    if (t.parameter == "viscous") {
      viscous_tested = true;
      CHECK(t.p_value < 1e-6);
      CHECK(t.dof == 1);
    }
  }
  CHECK(viscous_tested);
}

namespace {

// Direction-dependent friction on the same swing: tau_c+ 0.4 / tau_c- 0.2
// and b+ 0.25 / b- 0.15, J 0.05.
AxisLog AsymmetricLog(unsigned seed) {
  return SwingWith(
      [](double, double, double qd, double qdd) {
        return 0.05 * qdd + (qd > 0 ? 0.4 + 0.25 * qd : (qd < 0 ? -0.2 + 0.15 * qd : 0.0));
      },
      seed);
}

}  // namespace

TEST_CASE("axis: direction-dependent friction is named by the adequacy check and recovered by its terms") {
  const AxisLog log = AsymmetricLog(41);
  const AxisFitOutput classic = FitAxis({log}, AxisSection{}, {});
  CHECK(HasWarning(classic.fit, "direction-dependent friction"));
  AxisFitOptions options;
  options.free = {"inertia", "coulomb_pos", "coulomb_neg", "viscous_pos", "viscous_neg"};
  AxisSection no_offset;
  no_offset.offset = 0.0;
  const AxisFitOutput out = FitAxis({log}, no_offset, options);
  CHECK(out.params.coulomb_pos == Approx(0.4).epsilon(0.03));
  CHECK(out.params.coulomb_neg == Approx(0.2).epsilon(0.05));
  CHECK(out.params.viscous_pos == Approx(0.25).epsilon(0.03));
  CHECK(out.params.viscous_neg == Approx(0.15).epsilon(0.05));
  CHECK(out.params.inertia == Approx(0.05).epsilon(0.03));
  CHECK_FALSE(HasWarning(out.fit, "direction-dependent friction"));
  // The model function agrees with the generator.
  CHECK(CalcAxisForce(out.params, 0.0, 1.0, 0.0) == Approx(0.4 + 0.25).epsilon(0.03));
  CHECK(CalcAxisForce(out.params, 0.0, -1.0, 0.0) == Approx(-0.2 - 0.15).epsilon(0.05));
}

TEST_CASE("axis: an offset with both Coulomb directions, or coulomb with its replacement, is refused by name") {
  const AxisLog log = AsymmetricLog(42);
  AxisFitOptions both;
  both.free = {"inertia", "offset", "coulomb_pos", "coulomb_neg"};
  try {
    FitAxis({log}, AxisSection{{}, 0.2, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}}, both);
    FAIL("no refusal");
  } catch (const IdentificationError& e) {
    const std::string message = e.what();
    CHECK(message.find("offset") != std::string::npos);
    CHECK(message.find("coulomb_pos") != std::string::npos);
    CHECK(message.find("coulomb_neg") != std::string::npos);
  }
  AxisFitOptions twice;
  twice.free = {"inertia", "coulomb", "coulomb_pos", "viscous"};
  CHECK_THROWS_AS(FitAxis({log}, AxisSection{}, twice), OptionError);
  CHECK(AxisParameterCount() == AxisTermsZeroUnlessGiven().size() + 4);  // J, b, tau_c, tau_0 needed
}

TEST_CASE("feed-forward: Kg and Kg_angle from the gravity terms cover the truth; first-order std matches sampling") {
  // SwingLog's gravity -3.0 cos q + 0.8 sin q = Kg cos(q - Kg_angle).
  const double kg = std::hypot(-3.0, 0.8), angle = std::atan2(0.8, -3.0);
  AxisFitOptions with_gravity;
  with_gravity.free = {"inertia", "viscous", "coulomb", "gravity_cos", "gravity_sin"};
  AxisSection known_offset;
  known_offset.offset = 0.1;
  int covered_kg = 0, covered_angle = 0;
  for (unsigned seed : {51u, 52u, 53u, 54u}) {
    const AxisFitOutput out = FitAxis({SwingLog(0.2, -3.0, 0.8, 0.0, seed)}, known_offset, with_gravity);
    const Feedforward ff = CalcAxisFeedforward(out.params, out.fit, "N m", "rad", true);
    std::map<std::string, FeedforwardGain> gain;
    for (const auto& g : ff.gains) gain[g.key] = g;
    REQUIRE(gain.count("Kg") == 1);
    REQUIRE(gain.count("Kg_angle") == 1);
    REQUIRE(gain.count("offset") == 1);  // given, so fixed: std 0
    CHECK(gain["offset"].value == 0.1);
    CHECK(gain["offset"].standard_error == 0.0);
    CHECK(gain["Ks"].value == Approx(0.3).epsilon(0.05));
    CHECK(gain["Kv"].unit == "N m s/rad");
    CHECK(gain["Ka"].unit == "N m s^2/rad");
    covered_kg += std::abs(gain["Kg"].value - kg) < 2.0 * gain["Kg"].standard_error;
    covered_angle += std::abs(gain["Kg_angle"].value - angle) < 2.0 * gain["Kg_angle"].standard_error;
  }
  CHECK(covered_kg >= 3);
  CHECK(covered_angle >= 3);
  // The first-order std against sampling the estimates from N(value, C).
  FitResult fit;
  fit.estimates = {{"gravity_cos", -3.0, 0.05}, {"gravity_sin", 0.8, 0.08}};
  fit.covariance = {0.05 * 0.05, 0.3 * 0.05 * 0.08, 0.3 * 0.05 * 0.08, 0.08 * 0.08};
  AxisParameters p;
  p.gravity_cos = -3.0;
  p.gravity_sin = 0.8;
  const Feedforward ff = CalcAxisFeedforward(p, fit, "N m", "rad", false);
  std::mt19937 random(7);
  std::normal_distribution<double> z(0.0, 1.0);
  const double l11 = 0.05, l21 = 0.3 * 0.08, l22 = 0.08 * std::sqrt(1.0 - 0.09);
  double s_kg = 0.0, s2_kg = 0.0, s_angle = 0.0, s2_angle = 0.0;
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    const double z1 = z(random), z2 = z(random);
    const double gc = -3.0 + l11 * z1, gs = 0.8 + l21 * z1 + l22 * z2;
    const double a = std::hypot(gc, gs), phi = std::atan2(gs, gc);
    s_kg += a;
    s2_kg += a * a;
    s_angle += phi;
    s2_angle += phi * phi;
  }
  const double sd_kg = std::sqrt(s2_kg / n - (s_kg / n) * (s_kg / n));
  const double sd_angle = std::sqrt(s2_angle / n - (s_angle / n) * (s_angle / n));
  REQUIRE(ff.gains.size() == 4);  // Ks, Kv (fixed: std 0), Kg, Kg_angle
  CHECK(ff.gains[0].standard_error == 0.0);
  CHECK(ff.gains[2].key == "Kg");
  CHECK(ff.gains[2].standard_error == Approx(sd_kg).epsilon(0.02));
  CHECK(ff.gains[3].standard_error == Approx(sd_angle).epsilon(0.02));
}

TEST_CASE("feed-forward: direction-dependent terms give Ks and Kv per direction with summed variance") {
  FitResult fit;
  fit.estimates = {{"coulomb", 0.3, 0.02}, {"coulomb_pos", 0.1, 0.03}};
  fit.covariance = {0.0004, -0.0002, -0.0002, 0.0009};
  AxisParameters p;
  p.coulomb = 0.3;
  p.coulomb_pos = 0.1;
  p.offset = 0.05;  // given, not fitted: std 0
  const Feedforward ff = CalcAxisFeedforward(p, fit, "V", "Meters", false);
  REQUIRE(ff.gains.size() == 4);
  CHECK(ff.gains[0].key == "Ks_forward");
  CHECK(ff.gains[0].value == Approx(0.4));
  CHECK(ff.gains[0].standard_error == Approx(std::sqrt(0.0004 + 0.0009 - 2 * 0.0002)));
  CHECK(ff.gains[1].key == "Ks_backward");
  CHECK(ff.gains[1].standard_error == Approx(0.02));
  CHECK(ff.gains[2].key == "Kv");
  CHECK(ff.gains[2].unit == "V s/Meters");
  CHECK(ff.gains[3].key == "offset");
  CHECK(ff.gains[3].value == 0.05);
  CHECK(ff.gains[3].standard_error == 0.0);
}

TEST_CASE("axis IDIM-LS: the nonlinear Stribeck term is refused by name, fixed or free") {
  const AxisLog log = AsymmetricLog(43);
  AxisFitOptions free_stribeck;
  free_stribeck.free = {"inertia", "viscous", "coulomb", "offset", "stribeck"};
  CHECK_THROWS_WITH(FitAxis({log}, AxisSection{}, free_stribeck),
                    Catch::Contains("‹free› stribeck") && Catch::Contains("‹method› oe"));
  AxisSection given;
  AxisValue(given, "stribeck") = 0.2;
  AxisValue(given, "stribeck_velocity") = 0.5;
  CHECK_THROWS_WITH(FitAxis({log}, given, {}), Catch::Contains("axis.stribeck = 0.2") && Catch::Contains("‹method› oe"));
  // The model function carries the excess: at v = v_s it is tau_s / e.
  AxisParameters p;
  p.coulomb = 1.0;
  AxisValue(p, "stribeck") = 0.2;
  AxisValue(p, "stribeck_velocity") = 0.5;
  CHECK(CalcAxisForce(p, 0.0, 0.5, 0.0) == Approx(1.0 + 0.2 / std::exp(1.0)));
  CHECK(CalcAxisForce(p, 0.0, -0.5, 0.0) == Approx(-1.0 - 0.2 / std::exp(1.0)));
  CHECK(CalcAxisForce(p, 0.0, 0.0, 0.0) == 0.0);
}

namespace {
// The warning that starts with `start`, or "".
std::string WarningText(const FitResult& fit, const std::string& start) {
  for (const auto& w : fit.warnings) {
    if (w.rfind(start, 0) == 0) return w;
  }
  return "";
}
}  // namespace

TEST_CASE("axis processing advice: a measured rate is suggested only to logs without one") {
  // A cutoff at the multisine's top component (2.3 Hz, which dominates q''):
  // the inertia moves with the cutoff, with or without a measured rate.
  AxisExperiment e;
  e.noise = 0.05;
  e.duration = 25.0;
  const AxisLog without_rate = SimulateAxisExperiment(kTruth, e);
  AxisLog with_rate = without_rate;
  // qd in closed form from the profile in sim/axis_experiment.h (A = 1).
  const double w1 = 2.0 * M_PI * 0.3, w2 = 2.0 * M_PI * 1.1, w3 = 2.0 * M_PI * 2.3;
  for (const double t : with_rate.time) {
    with_rate.rate.push_back(0.6 * w1 * std::cos(w1 * t) + 0.3 * w2 * std::cos(w2 * t + 1.0) +
                             0.1 * w3 * std::cos(w3 * t + 2.0));
  }
  AxisFitOptions options;
  options.cutoff = 2.0;
  const AxisSection start{0.1, 0.5, 2.0, 0.0, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}};
  const std::string differentiated = WarningText(FitAxis({without_rate}, start, options).fit, "processing: inertia");
  const std::string measured = WarningText(FitAxis({with_rate}, start, options).fit, "processing: inertia");
  REQUIRE_FALSE(differentiated.empty());
  REQUIRE_FALSE(measured.empty());
  CHECK(differentiated.find("try a measured rate qd") != std::string::npos);
  CHECK(measured.find("try a measured rate qd") == std::string::npos);
  CHECK(measured.find("the measured rate qd is used") != std::string::npos);
}

TEST_CASE("axis advice: gravity terms collinear with the offset over a short stroke are not suggested") {
  // A force growing with q^2 over +-0.06 rad (400 (1 - cos q) to 0.1 %): it
  // follows cos q, but cos q stays within 0.2 % of 1 there, the offset's
  // twin: "fitting" it gives offset ~ +400 and g_c ~ -400 (the issue's
  // +356.6 N / -358.8 N on a ball screw).
  const AxisLog log = SwingWith(
      [](double, double q, double qd, double qdd) {
        return 0.05 * qdd + 0.2 * qd + 0.3 * ((qd > 0) - (qd < 0)) + 0.1 + 200.0 * q * q;
      },
      5, 0.075);
  // The unexplained force leaves viscous barely determined (about 80 %
  // relative std at the cutoffs below the band): the advice is what is
  // checked here, so the fit is not refused for it.
  AxisFitOptions lenient;
  lenient.max_relative_std = 2.0;
  const AxisFitOutput out = FitAxis({log}, AxisSection{}, lenient);
  const std::string warning = WarningText(out.fit, "position-dependent force");
  INFO(fmt::format("{}", fmt::join(out.fit.warnings, "\n")));
  REQUIRE_FALSE(warning.empty());
  CHECK(warning.find("--free") == std::string::npos);
  CHECK_FALSE(HasWarning(out.fit, "gravity missing?"));
  // On a linear axis there is no cos q / sin q test at all, and the terms are refused.
  AxisSection linear;
  linear.linear = true;
  const AxisFitOutput on_linear = FitAxis({log}, linear, lenient);
  CHECK(WarningText(on_linear.fit, "position-dependent force").empty());
  CHECK_FALSE(HasWarning(on_linear.fit, "gravity missing?"));
  AxisFitOptions with_gravity;
  with_gravity.free = {"inertia", "viscous", "coulomb", "offset", "gravity_cos"};
  CHECK_THROWS_WITH(FitAxis({log}, linear, with_gravity), Catch::Contains("‹free› gravity_cos: a linear axis"));
  linear.gravity_sin = 2.0;
  CHECK_THROWS_WITH(FitAxis({log}, linear, {}), Catch::Contains("axis.gravity_sin = 2 on a linear axis"));
}

TEST_CASE("torque timing: the second difference of q sees a held command as (u_(k-1) + u_k) / 2") {
  // J q'' = u - tau_0 with u held over each 1 ms step, integrated exactly.
  const double inertia = 0.05, offset = 0.3, h = 1e-3;
  std::vector<double> position, command;
  double q = 0.0, v = 0.0;
  for (int k = 0; k <= 2000; ++k) {
    const double t = k * h;
    // A command that jumps every 37 ms about a multisine (a position loop's output).
    const double u = 0.6 * std::sin(2 * M_PI * 0.7 * t) + 0.3 * std::sin(2 * M_PI * 3.1 * t + 1.0) +
                     0.2 * ((k / 37) % 3 == 0 ? 1.0 : -0.5) + offset;
    position.push_back(q);
    command.push_back(u);
    const double a = (u - offset) / inertia;
    q += v * h + 0.5 * a * h * h;
    v += a * h;
  }
  const auto held = TimedAxisTorque(command, AxisTorqueTiming::kHeld);
  CHECK(TimedAxisTorque(command, AxisTorqueTiming::kSampled) == command);
  CHECK(held[0] == command[0]);
  double held_error = 0.0, sampled_error = 0.0;
  for (std::size_t k = 1; k + 1 < position.size(); ++k) {
    const double second_difference = (position[k + 1] - 2.0 * position[k] + position[k - 1]) / (h * h);
    held_error = std::max(held_error, std::abs(inertia * second_difference - (held[k] - offset)));
    sampled_error = std::max(sampled_error, std::abs(inertia * second_difference - (command[k] - offset)));
  }
  CHECK(held_error < 1e-9);      // exact to rounding
  CHECK(sampled_error > 0.1);    // half of each jump of the command (0.75 / 2)
}

TEST_CASE("torque timing names: AxisTorqueTimingFromName inverts AxisTorqueTimingName and refuses others by name") {
  for (const AxisTorqueTiming t : {AxisTorqueTiming::kSampled, AxisTorqueTiming::kHeld, AxisTorqueTiming::kFromData}) {
    CHECK(AxisTorqueTimingFromName(AxisTorqueTimingName(t)) == t);
  }
  CHECK_THROWS_WITH(AxisTorqueTimingFromName("Held"), Catch::Contains("‹torque-timing› Held: not one of sampled, held, auto"));
  CHECK_THROWS_AS(AxisTorqueTimingFromName("sampled (smoothed)"), OptionError);
  // The choices the options offer, in the order given.
  CHECK(AxisTorqueTimingNames({AxisTorqueTiming::kFromData, AxisTorqueTiming::kSampled, AxisTorqueTiming::kHeld}) ==
        std::vector<std::string>{"auto", "sampled", "held"});
}

TEST_CASE("exclusion reach: 4 decimations at the decimated band, longer below it, the pair settled beyond it") {
  // The friction step through the sharpened position filter and the
  // decimation filter, pushed here apart from AxisExclusionReach: beyond
  // the reach it returns, less than kAxisExclusionSettled of the step is
  // left; within it, more. Below kAxisExclusionLowestCutoff of the band the
  // reach stays that cutoff's.
  const double rate = 1000.0;
  const int decimation = 10;
  const double band = AxisDecimatedBand(rate, decimation);
  // The sharpened pair leaves 2.7 % of the step at 2 decimations, 0.81 % at
  // 3 and 0.12 % at 4 (docs/models.md#axis-exclusion).
  CHECK(AxisExclusionReach(rate, band, decimation) == 4 * decimation);
  CHECK(AxisExclusionReach(0.0, band, decimation) == kAxisExclusionDecimationsIrregular * decimation);
  CHECK(AxisExclusionReach(rate, band / 4.0, decimation) ==
        AxisExclusionReach(rate, kAxisExclusionLowestCutoff * band, decimation));
  int previous = 0;
  for (const double cutoff : {band, 0.75 * band, kAxisExclusionLowestCutoff * band}) {
    const int reach = AxisExclusionReach(rate, cutoff, decimation);
    INFO("cutoff " << cutoff << " Hz: reach " << reach << " samples");
    CHECK(reach % decimation == 0);
    CHECK(reach >= previous);
    previous = reach;
    std::vector<double> step(4001, 0.0);
    for (std::size_t k = 2000; k < step.size(); ++k) step[k] = 1.0;
    std::vector<double> twice = ZeroPhaseLowPass(ZeroPhaseLowPass(step, cutoff, rate), cutoff, rate);
    const std::vector<double> thrice = ZeroPhaseLowPass(twice, cutoff, rate);
    for (std::size_t k = 0; k < step.size(); ++k) twice[k] = 3.0 * twice[k] - 2.0 * thrice[k];
    const std::vector<double> pair = ZeroPhaseLowPass(twice, band, rate);
    double beyond = 0.0, within = 0.0;
    for (std::size_t k = 0; k < step.size(); ++k) {
      const std::size_t distance = k >= 2000 ? k - 2000 : 2000 - k;
      double& largest = distance > static_cast<std::size_t>(reach) ? beyond : within;
      largest = std::max(largest, std::abs(pair[k] - step[k]));
    }
    CHECK(beyond <= kAxisExclusionSettled);
    CHECK(within > kAxisExclusionSettled);
  }
  // Half the band spreads the step further than the band.
  CHECK(AxisExclusionReach(rate, band / 2.0, decimation) > AxisExclusionReach(rate, band, decimation));
}

TEST_CASE("cutoff pick: the highest unless a lower one wins by the margin; refused candidates never win") {
  const std::vector<double> candidates{5.0, 10.0, 20.0, 40.0};
  const auto pick = [&](std::map<double, double> score) {
    return PickAxisCutoff(candidates, [&](double c) { return score.at(c); });
  };
  // Ties and small gains keep the band.
  CHECK(pick({{5.0, 1.0}, {10.0, 1.0}, {20.0, 0.97}, {40.0, 1.0}}) == 40.0);
  // A clear gain moves down; the next one is measured against the new holder.
  CHECK(pick({{5.0, 0.9}, {10.0, 0.9}, {20.0, 0.94}, {40.0, 1.0}}) == 20.0);
  CHECK(pick({{5.0, 0.5}, {10.0, 0.9}, {20.0, 0.94}, {40.0, 1.0}}) == 5.0);
  // A refused band (+inf) gives way to the first candidate that fits.
  CHECK(pick({{5.0, 1.95}, {10.0, 2.0}, {20.0, HUGE_VAL}, {40.0, HUGE_VAL}}) == 10.0);
  // All refused: the band (the fit and the validation agree on it).
  CHECK(pick({{5.0, HUGE_VAL}, {10.0, HUGE_VAL}, {20.0, HUGE_VAL}, {40.0, HUGE_VAL}}) == 40.0);
  CHECK(PickAxisCutoff({}, [](double) { return 1.0; }) == 0.0);
}

TEST_CASE("row reaches: at the band the fit's rows and the search's agree; irregular logs keep the shortest") {
  const double rate = 1000.0;
  const int decimation = 10;
  const double band = AxisDecimatedBand(rate, decimation);
  CHECK(AxisRowReach(rate, band, decimation, AxisReach::kAtCutoff) ==
        AxisRowReach(rate, band / 2.0, decimation, AxisReach::kAtBand));
  CHECK(AxisRowReach(rate, band / 2.0, decimation, AxisReach::kAtCutoff) >
        AxisRowReach(rate, band / 2.0, decimation, AxisReach::kAtBand));
  CHECK(AxisShortestReach(rate, decimation) == kAxisExclusionDecimations * decimation);
  CHECK(AxisShortestReach(0.0, decimation) == kAxisExclusionDecimationsIrregular * decimation);
  CHECK(AxisRowReach(0.0, band, decimation, AxisReach::kAtCutoff) == AxisShortestReach(0.0, decimation));
}

TEST_CASE("torque delay: a number spells kDelayed; its rows are the held rows moved, exactly at whole samples") {
  double delay = 9.0;
  CHECK(ParseAxisTorqueTiming("-0.5", delay) == AxisTorqueTiming::kDelayed);
  CHECK(delay == -0.5);
  CHECK(ParseAxisTorqueTiming("held", delay) == AxisTorqueTiming::kHeld);
  CHECK_THROWS_WITH(ParseAxisTorqueTiming("1.5", delay), Catch::Contains("from -1 to 1"));
  CHECK(DescribeAxisTorqueTiming(AxisTorqueTiming::kDelayed, -0.5) == "delay -0.500 samples");
  // A log whose torque column is the held one's moved one sample later (as
  // ros2_control writes the command held over the step before): read with
  // delay -0.5 its rows equal the held log's rows one sample earlier, the
  // same regressors against the same torque.
  AxisExperiment e;
  e.duration = 4.0;
  const AxisLog held = SimulateAxisExperiment(kTruth, e);
  AxisLog later = held;
  for (std::size_t k = later.force.size(); k-- > 1;) later.force[k] = held.force[k - 1];
  const auto names = AxisRowColumnNames();
  const AxisRows a = BuildAxisRows({held}, 20.0, 1, 0.01, names, AxisTorqueTiming::kHeld);
  const AxisRows b = BuildAxisRows({later}, 20.0, 1, 0.01, names, AxisTorqueTiming::kDelayed, AxisReach::kAtCutoff, -0.5);
  REQUIRE(a.regression.rows() > 100);
  // Row r of b stands at sample k and holds the held rows' values of k - 1.
  std::size_t compared = 0;
  for (std::size_t r = 0; r < b.regression.rows(); ++r) {
    for (std::size_t s = 0; s < a.regression.rows(); ++s) {
      if (std::abs(a.time[s] - (b.time[r] - (held.time[1] - held.time[0]))) > 1e-9) continue;
      CHECK(b.measured[r] == Approx(a.measured[s]).margin(1e-12));
      for (std::size_t c = 0; c < AxisLinearCount(); ++c) CHECK(b.regression.at(r, c) == Approx(a.regression.at(s, c)).margin(1e-9));
      ++compared;
    }
  }
  CHECK(compared > 100);
}

namespace {

// A jittered-stamp log written here, in closed form (not by lib/sim): two
// sines, tau = J q'' + b q' + tau_c sgn q', moving at both ends.
AxisLog JitteredSineLog(double rate, double duration, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.1 / rate, 0.1 / rate);
  std::normal_distribution<double> noise(0.0, 0.1);
  AxisLog log{"jittered.csv", {}, {}, {}, {}};
  const double w1 = 2.0 * M_PI * 0.7, w2 = 2.0 * M_PI * 1.9;
  for (int k = 0; k < static_cast<int>(duration * rate); ++k) {
    const double t = 0.3 + k / rate + jitter(rng);
    const double q = 0.8 * std::sin(w1 * t) + 0.2 * std::sin(w2 * t);
    const double qd = 0.8 * w1 * std::cos(w1 * t) + 0.2 * w2 * std::cos(w2 * t);
    const double qdd = -0.8 * w1 * w1 * std::sin(w1 * t) - 0.2 * w2 * w2 * std::sin(w2 * t);
    log.time.push_back(t);
    log.position.push_back(q);
    log.force.push_back(0.3 * qdd + 2.5 * qd + 0.25 * ((qd > 0) - (qd < 0)) + noise(rng));
  }
  return log;
}

AxisLog StampsOnly(double rate, int samples) {
  AxisLog log{"stamps.csv", {}, {}, {}, {}};
  for (int k = 0; k < samples; ++k) log.time.push_back(k / rate);
  log.position.assign(log.time.size(), 0.0);
  log.force.assign(log.time.size(), 0.0);
  return log;
}

}  // namespace

TEST_CASE("axis decimation from the logs: every sample at 50 Hz, every 2nd at 200 Hz, every 10th at 1 kHz") {
  std::string rule;
  CHECK(ChooseAxisDecimation({StampsOnly(50.0, 300)}, &rule) == 1);
  CHECK(rule.find("50 Hz") != std::string::npos);
  CHECK(ChooseAxisDecimation({StampsOnly(200.0, 2000)}, nullptr) == 2);
  CHECK(ChooseAxisDecimation({StampsOnly(1000.0, 10000)}, nullptr) == 10);
  CHECK(ChooseAxisDecimation({StampsOnly(5000.0, 50000)}, nullptr) == kAxisDecimation);
  // The lowest rate decides; the shortest log keeps at least 40 rows.
  CHECK(ChooseAxisDecimation({StampsOnly(1000.0, 10000), StampsOnly(200.0, 2000)}, nullptr) == 2);
  CHECK(ChooseAxisDecimation({StampsOnly(1000.0, 10000), StampsOnly(1000.0, 120)}, &rule) == 3);
  CHECK(rule.find("120 samples") != std::string::npos);
}

TEST_CASE("axis: a jittered 50 Hz log keeps every sample, resampled onto its mean step") {
  // Stamps that jitter about 20 ms (a DataLog's loop) are resampled onto the
  // mean step (a note says so) and take the constant-rate path: every sample
  // a row, each interval holding the truth.
  for (unsigned seed : {1u, 2u, 3u}) {
    const AxisFitOutput out = FitAxis({JitteredSineLog(50.0, 20.0, seed)}, AxisSection{}, {});
    CHECK(out.decimation == 1);
    CHECK(std::any_of(out.fit.notes.begin(), out.fit.notes.end(),
                      [](const std::string& n) { return n.find("resampled") != std::string::npos; }));
    CHECK(out.method.find("irregular") == std::string::npos);
    for (const auto& [key, truth] : {std::pair{"inertia", 0.3}, {"viscous", 2.5}, {"coulomb", 0.25}}) {
      const std::string name = key;
      const auto e = std::find_if(out.fit.estimates.begin(), out.fit.estimates.end(),
                                  [&name](const ParameterEstimate& p) { return p.name == name; });
      REQUIRE(e != out.fit.estimates.end());
      INFO(name << " " << e->value << " [" << e->ci95_low << ", " << e->ci95_high << "] seed " << seed);
      CHECK(e->ci95_low <= truth);
      CHECK(truth <= e->ci95_high);
    }
  }
}
