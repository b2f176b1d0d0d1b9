#include "fit/joint/joint_oe_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sys/resource.h>
#include <cstdio>
#include <map>

#include <fmt/format.h>

#include "core/clipped_text.h"
#include "core/errors.h"
#include "core/option_check.h"
#include "fit/core/adequacy.h"
#include "fit/axis/axis_rows.h"
#include "fit/joint/joint_fit.h"
#include "fit/joint/joint_oe_residuals.h"
#include "fit/joint/joint_oe_segments.h"
#include "models/missing_values.h"
#include "sim/joint_simulator.h"

namespace driveid {

bool JointOeOptions::IsValid(std::string* error) const {
  return OptionCheck(error)
      .Require(segment_seconds >= 0.0, "‹segment›", segment_seconds, "segment >= 0 s (0: auto, inf: whole log)")
      .Nested(fit);
}
namespace {

using namespace joint_oe;

// A simulated deflection below this fit % (with correlated residuals) draws
// a warning: the angles' own fit % stays high whatever the spring does.
constexpr double kLowDeflectionFitPercent = 80.0;

std::string OeAdvice(const std::vector<std::string>& involved) {
  std::vector<std::string> advice;
  const auto has = [&](const std::string& key) {
    return std::find(involved.begin(), involved.end(), key) != involved.end();
  };
  const auto key = [](double JointParameters::*member) { return KeyOf(JointParameterTable(), member); };
  if (has(key(&JointParameters::stiffness)) || has(key(&JointParameters::damping))) {
    advice.push_back("stiffness and damping need the joint to deflect: excite it across its resonance");
  }
  if (has("offset") && has(key(&JointParameters::motor_coulomb))) {
    advice.push_back("the offset and Coulomb friction separate only with motion in both directions");
  }
  if (has("gravity_cos") || has("gravity_sin")) advice.push_back("gravity terms need the link to move through angles");
  if (has(key(&JointParameters::motor_inertia)) && has(key(&JointParameters::link_inertia))) {
    advice.push_back("only the total J_m + J_l is determined: fix one of them in ‹params› (a motor's data-sheet "
                     "inertia for motor_inertia) and leave it out of ‹free›");
  }
  // The initial states are internal: what the user can change is where the log starts.
  const bool start_state = std::any_of(involved.begin(), involved.end(), [](const std::string& name) {
    return name.find("(t0)") != std::string::npos;
  });
  if (start_state) {
    advice.push_back("the log's start does not determine the joint's initial state (the simulation starts from it): "
                     "crop the log with ‹from› to begin where the joint moves in both angles, or log qd_motor and "
                     "qd_link");
  }
  const bool segment_state = std::any_of(involved.begin(), involved.end(), [](const std::string& name) {
    return name.find("(t=") != std::string::npos;
  });
  if (segment_state) {
    advice.push_back("a segment's start does not determine the joint's state there (each segment is simulated from "
                     "its own): lengthen the segments with ‹segment›, or simulate each log whole with ‹segment› none");
  }
  return fmt::format("{}", fmt::join(advice, "; "));
}

}  // namespace

std::vector<std::string> JointOeDefaultFree(const std::vector<JointLog>& logs) {
  std::vector<std::string> free = JointDefaultFree(logs);
  const std::string link_coulomb = KeyOf(JointParameterTable(), &JointParameters::link_coulomb);
  free.erase(std::remove(free.begin(), free.end(), link_coulomb), free.end());
  return free;
}

void CheckOutputErrorSimulates(const JointSection& start, const std::vector<std::string>& free) {
  const std::string link_coulomb = KeyOf(JointParameterTable(), &JointParameters::link_coulomb);
  if (std::find(free.begin(), free.end(), link_coulomb) != free.end() || start.link_coulomb.value_or(0.0) != 0.0) {
    throw OptionError("‹method› oe does not simulate the link's Coulomb friction: leave link_coulomb out of ‹free› "
                      "and at 0 in ‹params›, or use ‹method› id");
  }
}

namespace {

// Start and fixed values; the free terms in table order, then tau_l0 (one
// per log with a shaft torque); every value the model needs and the file
// lacks named in one message.
struct JointOeDesign {
  JointParameters fixed;
  std::vector<int> terms;
  std::vector<FitParameter> parameters;
  int offsets = 0;
};

JointOeDesign MakeJointOeDesign(const std::vector<JointLog>& logs, const JointSection& start,
                                const JointParameters* initial, const std::vector<std::string>& free,
                                std::vector<OeLog>& oe) {
  const std::string offset_key = KeyOf(JointParameterTable(), &JointParameters::link_torque_offset);
  const auto is_free = [&](const std::string& key) { return std::find(free.begin(), free.end(), key) != free.end(); };
  JointOeDesign d;
  std::vector<const ParameterSpec*> needed;
  if (!start.gear_ratio || !(*start.gear_ratio > 0.0)) {
    needed.push_back(&SpecOf(JointParameterTable(), &JointSection::gear_ratio));
  }
  for (int j = 0; j <= kJointGravitySin; ++j) {
    const auto& row = JointParameterTable()[static_cast<std::size_t>(j)];
    const std::optional<double> given_value = start.*(row.in_section);
    double value = given_value.value_or(0.0);
    if (is_free(row.spec.key)) {
      const double guess = initial != nullptr ? (*initial).*(row.in_model) : value;
      const bool positive = j == kJointMotorInertia || j == kJointLinkInertia || j == kJointStiffness;
      value = positive && !(guess > 0.0) ? value : std::max(guess, row.spec.lower_bound);
      if (positive && !(value > 0.0)) {
        throw InputError(fmt::format("‹method› oe: joint.{} needs a start value > 0 in ‹params› (the inverse-dynamics "
                                     "start did not give one)",
                                     row.spec.key));
      }
      d.terms.push_back(j);
      d.parameters.push_back({row.spec.key, value, row.spec.lower_bound, value != 0.0 ? 0.0 : 1e-3});
    } else if (!given_value && row.spec.default_free && j != kJointLinkCoulomb) {
      needed.push_back(&row.spec);
    }
    d.fixed.*(row.in_model) = value;
  }
  if (!needed.empty()) {
    throw MissingValuesError("‹params›", "joint", needed, "(fixed in this fit)", " (or name the fitted ones in ‹free›)");
  }
  if (!(d.fixed.motor_inertia > 0.0) || !(d.fixed.link_inertia > 0.0)) {
    throw InputError("‹method› oe: the joint needs both inertias > 0: give joint.motor_inertia and joint.link_inertia");
  }
  d.fixed.link_torque_offset = start.link_torque_offset.value_or(0.0);
  if (is_free(offset_key)) {
    const double value = initial != nullptr ? initial->link_torque_offset : d.fixed.link_torque_offset;
    for (std::size_t i = 0; i < oe.size(); ++i) {
      if (logs[i].link_torque.empty()) continue;
      oe[i].offset_parameter = static_cast<int>(d.terms.size()) + d.offsets++;
      d.parameters.push_back({logs.size() > 1 ? fmt::format("{}_{}", offset_key, i + 1) : offset_key, value,
                              -HUGE_VAL, 0.0});
    }
  }
  return d;
}

// Each log cut into segments of `seconds` (multiple shooting) with their
// initial states as nuisance parameters (a sticking motor that starts a
// segment at rest keeps its start rate at 0).
void AddShots(std::vector<OeLog>& oe, double seconds, double n, std::vector<FitParameter>& parameters) {
  static const char* const kNames[] = {"q_motor", "qd_motor", "q_link", "qd_link"};
  for (std::size_t i = 0; i < oe.size(); ++i) {
    const JointLog& log = *oe[i].log;
    for (OeSegment& segment : SplitLog(log, oe[i].torque, n, SegmentSamples(log, seconds))) {
      OeShot shot{std::move(segment), {-1, -1, -1, -1}};
      const std::array<double, 4>& x0 = shot.segment.x0;
      const std::string suffix = oe.size() > 1 ? fmt::format("_{}", i + 1) : "";
      const std::string at = shot.segment.begin == 0 ? "t0" : fmt::format("t={:.6g} s", log.time[shot.segment.begin]);
      for (std::size_t s = 0; s < 4; ++s) {
        if (s == 1 && !shot.segment.motor_moving) continue;
        shot.start_parameter[s] = static_cast<int>(parameters.size());
        const double scale = s % 2 == 0 ? std::max(std::abs(x0[2]), 1e-3) : std::max(std::abs(x0[s]), 1e-3);
        parameters.push_back({fmt::format("{}({}){}", kNames[s], at, suffix), x0[s], -HUGE_VAL, scale});
      }
      oe[i].shots.push_back(std::move(shot));
    }
  }
}

// The segments' row clusters (every channel's rows of a segment) when there
// are several, else none.
std::vector<std::vector<RowRange>> ShotClusters(const std::vector<OeLog>& oe) {
  std::vector<std::vector<RowRange>> clusters;
  for (const auto& l : oe) {
    for (const auto& shot : l.shots) {
      std::vector<RowRange> rows;
      for (const auto& c : l.channels) {
        rows.push_back({c.first_row + static_cast<int>(shot.segment.begin),
                        static_cast<int>(shot.segment.end - shot.segment.begin)});
      }
      clusters.push_back(std::move(rows));
    }
  }
  if (clusters.size() < 2) clusters.clear();
  return clusters;
}

// Two passes: weighted by the channels' spread, then by the first pass's
// residual noise; RMSE reported back in the channels' units.
FitResult FitTwoPasses(std::vector<OeLog>& oe, Residuals& residuals, std::vector<FitParameter> parameters,
                       const FitOptions& fit_options) {
  std::vector<FitChannel> channels;
  SetWeighted(oe, &channels);
  FitOptions first_pass = fit_options;
  first_pass.identifiability_threshold = 0.0;  // judged on the final fit
  const FitResult first = FitLeastSquares(residuals, parameters, channels, first_pass);
  for (std::size_t j = 0; j < parameters.size(); ++j) parameters[j].initial = first.estimates[j].value;
  std::size_t c = 0;
  for (auto& l : oe) {
    for (auto& ch : l.channels) {
      const double rmse = first.channels[c++].rmse / ch.weight;
      if (rmse > 0.0) ch.weight = 1.0 / rmse;
    }
  }
  SetWeighted(oe, &channels);
  FitResult fit = FitLeastSquares(residuals, parameters, channels, fit_options);
  c = 0;
  for (const auto& l : oe) {
    for (const auto& ch : l.channels) fit.channels[c++].rmse /= ch.weight;
  }
  return fit;
}

// The deflection q_motor / n - q_link is what the spring sees; the angles'
// fit % hides a poor fit of it behind the motion. Judged on each log
// simulated whole (`motor`, `link`): segments restart from fitted states and
// so hide a model error (link Coulomb friction) that a whole run shows, while
// a noisy torque's drift is of the rigid-body motion, which the deflection
// (a damped spring) does not accumulate.
void CheckDeflections(const std::vector<JointLog>& logs, double n, const std::vector<std::vector<double>>& motor,
                      const std::vector<std::vector<double>>& link, JointOeOutput& out) {
  for (std::size_t i = 0; i < logs.size(); ++i) {
    std::vector<double> measured, residual;
    for (std::size_t k = 0; k < logs[i].time.size(); ++k) {
      measured.push_back(logs[i].motor_position[k] / n - logs[i].link_position[k]);
      residual.push_back(measured.back() - (motor[i][k] / n - link[i][k]));
    }
    const ChannelStatistics d = DescribeResiduals(logs[i].path + ":deflection q_motor/n - q_link", measured.data(),
                                                  residual.data(), static_cast<int>(measured.size()));
    out.deflection_fit_percent.push_back(d.fit_percent);
    if (d.fit_percent < kLowDeflectionFitPercent && d.autocorrelation >= kLowFitMinAutocorrelation) {
      out.fit.warnings.push_back(fmt::format(
          "low fit: {}: the simulated deflection fits {:.1f} % (below {:.0f} %, residual lag-1 {:.2f}): the model misses what was "
          "measured (link Coulomb friction, which output error does not simulate? backlash?)",
          d.name, d.fit_percent, kLowDeflectionFitPercent, d.autocorrelation));
    }
  }
}

// Says how the logs were simulated: one run per log, or segments.
void DescribeShots(const std::vector<OeLog>& oe, JointOeOutput& out) {
  double seconds = 0.0;
  for (const auto& l : oe) {
    for (const auto& shot : l.shots) {
      out.segments += 1;
      seconds += shot.segment.time.back() - shot.segment.time.front();
    }
  }
  out.segment_seconds = seconds / static_cast<double>(std::max<std::size_t>(out.segments, 1));
  if (out.segments > oe.size()) {
    out.fit.notes.push_back(fmt::format(
        "output error by multiple shooting: {} segments of {:.3g} s, each simulated from its own fitted initial "
        "state (a measured torque's noise drifts over one segment only); intervals cluster-robust over the segments "
        "(docs/models.md#joint-output-error)",
        out.segments, out.segment_seconds));
  } else {
    out.fit.notes.push_back("output error by single shooting: each log simulated whole from its initial state");
  }
}

}  // namespace

namespace {

// One output-error fit with segments of options.segment_seconds (> 0;
// infinite: single shooting).
JointOeOutput FitShots(const std::vector<JointLog>& logs, const JointSection& start, const JointParameters* initial,
                       const JointOeOptions& options) {
  const std::string offset_key = KeyOf(JointParameterTable(), &JointParameters::link_torque_offset);
  std::vector<OeLog> oe;  // each log's channels, refused by name before the missing values
  if (start.gear_ratio && *start.gear_ratio > 0.0) oe = PrepareLogs(logs, *start.gear_ratio);
  JointOeDesign d = MakeJointOeDesign(logs, start, initial, options.free, oe);
  const double n = *start.gear_ratio;
  // The initial states are nuisance parameters, dropped from the result.
  const std::size_t reported = d.parameters.size();
  AddShots(oe, options.segment_seconds, n, d.parameters);
  std::vector<bool> keep(d.parameters.size(), false);
  std::fill(keep.begin(), keep.begin() + static_cast<std::ptrdiff_t>(reported), true);

  const auto tolerance = Tolerances(logs, n);
  const std::unique_ptr<Residuals> made =
      MakeResiduals(oe, d.fixed, d.terms, static_cast<int>(d.parameters.size()), n, tolerance[0], tolerance[1]);
  Residuals& residuals = *made;
  FitOptions fit_options = options.fit;
  if (!fit_options.advice) fit_options.advice = OeAdvice;
  fit_options.clusters = ShotClusters(oe);
  fit_options.normal_equations = !fit_options.clusters.empty();
  JointOeOutput out;
  out.fit = FitTwoPasses(oe, residuals, d.parameters, fit_options);
  std::vector<double> estimate;
  for (const auto& e : out.fit.estimates) estimate.push_back(e.value);
  DropParameters(out.fit, keep);
  out.params = d.fixed;
  for (std::size_t j = 0; j < d.terms.size(); ++j) out.params.*(JointParameterTable()[d.terms[j]].in_model) = estimate[j];
  if (d.offsets > 0) out.params.link_torque_offset = estimate[d.terms.size()];
  out.motor_angle.resize(oe.size());
  out.link_angle.resize(oe.size());
  std::vector<std::vector<double>> whole_motor(oe.size()), whole_link(oe.size());
  for (std::size_t i = 0; i < oe.size(); ++i) {
    residuals.SimulateAngles(estimate.data(), i, &out.motor_angle[i], &out.link_angle[i]);
    if (oe[i].shots.size() > 1) {
      residuals.SimulateWhole(estimate.data(), i, &whole_motor[i], &whole_link[i]);
    } else {
      whole_motor[i] = out.motor_angle[i];
      whole_link[i] = out.link_angle[i];
    }
  }
  CheckDeflections(logs, n, whole_motor, whole_link, out);
  DescribeShots(oe, out);
  if (options.per_log && logs.size() > 1) {
    JointOeOptions alone = options;
    alone.per_log = false;
    AddPerLogFits(out.fit, LogLabels(logs), [&](std::size_t i) {
      auto e = FitJointOutputError({logs[i]}, start, initial, alone).fit.estimates;
      e.erase(std::remove_if(e.begin(), e.end(), [&](const ParameterEstimate& x) { return x.name == offset_key; }),
              e.end());
      return e;
    });
  }
  std::vector<std::string> nonnegative;
  for (const auto& row : JointParameterTable()) {
    if (row.in_model != nullptr && row.spec.lower_bound == 0.0) nonnegative.emplace_back(row.spec.key);
  }
  std::map<std::string, double> start_values;
  for (const auto& p : d.parameters) start_values[p.name] = p.initial;
  RequireDetermined(out.fit, nonnegative, kMaxRelativeStd, out.fit.warnings, start_values);
  return out;
}

// The start values' joint, for the auto segment length: the
// inverse-dynamics start where it has inertias and a stiffness, else
// ‹params›.
JointParameters StartJoint(const JointSection& start, const JointParameters* initial) {
  if (initial != nullptr && initial->motor_inertia > 0.0 && initial->link_inertia > 0.0 && initial->stiffness > 0.0) {
    return *initial;
  }
  JointParameters p;
  p.motor_inertia = start.motor_inertia.value_or(0.0);
  p.link_inertia = start.link_inertia.value_or(0.0);
  p.stiffness = start.stiffness.value_or(0.0);
  return p;
}

}  // namespace

namespace {

// Memory this machine can give (MemAvailable, or the address-space limit if
// lower) [bytes]; 0 when unknown.
double AvailableMemory() {
  double available = 0.0;
  if (std::FILE* f = std::fopen("/proc/meminfo", "r")) {
    char line[256];
    while (std::fgets(line, sizeof line, f)) {
      unsigned long long kib = 0;
      if (std::sscanf(line, "MemAvailable: %llu kB", &kib) == 1) available = 1024.0 * static_cast<double>(kib);
    }
    std::fclose(f);
  }
  struct rlimit limit {};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    const double cap = static_cast<double>(limit.rlim_cur);
    available = available > 0.0 ? std::min(available, cap) : cap;
  }
  return available;
}

// What the fit will hold, refused up front when the machine lacks it (a
// 10 M-sample log once ended in bad_alloc after 8 GB): the Jacobian, rows
// (samples x channels) by columns (free terms + 4 states per segment), in
// doubles, with the residuals, the simulation's sensitivities and the
// normal equations' copies about 3 times that.
void RequireMemory(const std::vector<JointLog>& logs, const JointOeOptions& options, const JointParameters& p) {
  double rows = 0.0, segments = 0.0;
  const double seconds = options.segment_seconds != 0.0 ? options.segment_seconds : AutoSegmentSeconds(logs, p);
  for (const auto& log : logs) {
    const double channels = 2.0 + !log.motor_rate.empty() + !log.link_rate.empty();
    rows += channels * static_cast<double>(log.time.size());
    const double samples = static_cast<double>(SegmentSamples(log, seconds));
    segments += std::ceil(static_cast<double>(log.time.size()) / std::max(1.0, samples));
  }
  const double columns = static_cast<double>(options.free.size()) + 4.0 * segments;
  const double bytes = 3.0 * 8.0 * rows * (columns + 4.0);
  const double available = AvailableMemory();
  if (available > 0.0 && bytes > 0.8 * available) {
    throw IdentificationError(fmt::format(
        "output error on these logs would hold about {:.3g} GiB ({:.3g} residual rows by {:.0f} columns, 3 copies), "
        "and {:.3g} GiB are available: crop the logs (‹from›/‹to›), fit fewer or shorter logs, or use ‹method› id",
        bytes / 1073741824.0, rows, columns, available / 1073741824.0));
  }
}

}  // namespace

JointOeOutput FitJointOutputError(const std::vector<JointLog>& logs, const JointSection& start,
                                  const JointParameters* initial, const JointOeOptions& given) {
  RequireValid(given);
  if (logs.empty()) throw OptionError("no logs given");
  JointOeOptions options = given;
  if (options.free.empty()) options.free = JointOeDefaultFree(logs);
  CheckFreeNames(JointParameterTable(), "joint", options.free);
  CheckOutputErrorSimulates(start, options.free);
  RequireMemory(logs, options, StartJoint(start, initial));
  if (options.segment_seconds != 0.0) return FitShots(logs, start, initial, options);
  // Auto: the shortest segments (least drift) that determine every term —
  // from AutoSegmentSeconds, doubled while the fit is refused, up to the
  // whole log.
  const double longest = LongestDuration(logs);
  options.segment_seconds = AutoSegmentSeconds(logs, StartJoint(start, initial));
  std::vector<std::string> tried;
  for (;;) {
    try {
      JointOeOutput out = FitShots(logs, start, initial, options);
      for (const auto& t : tried) out.fit.notes.push_back(t);
      return out;
    } catch (const IdentificationError& e) {
      if (!(options.segment_seconds < longest / 2.0)) throw;  // the longest already: its refusal stands
      std::string why = e.what();
      why = ClippedText(why, 160);
      const double next = 2.0 * options.segment_seconds < longest / 2.0 ? 2.0 * options.segment_seconds : HUGE_VAL;
      tried.push_back(fmt::format("segments of {:.3g} s were refused ({}); {}", options.segment_seconds, why,
                                  std::isinf(next) ? std::string("each log simulated whole instead")
                                                   : fmt::format("lengthened to {:.3g} s", next)));
      options.segment_seconds = next;
    }
  }
}

}  // namespace driveid
