#include "report/joint_design_report.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <fmt/format.h>

namespace driveid {
namespace {

std::string UnitOf(const std::string& key) {
  const auto* row = FindParameter(JointParameterTable(), key);
  return row ? row->spec.unit : "";
}

Json CandidateJson(const JointDesign& d, const JointDesignCandidate& c) {
  Json stds = Json::object();
  for (std::size_t j = 0; j < d.free.size(); ++j) stds[d.free[j]] = c.predicted_std[j];
  Json lines = Json::array();
  for (std::size_t l = 0; l < d.frequency.size(); ++l) {
    lines.push_back({{"frequency", d.frequency[l]}, {"amplitude", c.amplitude[l]}, {"phase", c.phase[l]}});
  }
  return {{"name", c.name},
          {"predicted_std", stds},
          {"geometric_mean_relative_std", c.geometric_mean_relative_std},
          {"rms_torque", c.rms},
          {"binding_limit", c.binding},
          {"peaks", {{"torque", c.peak_torque}, {"speed", c.peak_speed}}},
          {"lines", lines}};
}

}  // namespace

std::string FormatJointDesign(const JointDesign& d) {
  std::string out = fmt::format("{:<18} {:>12} {:>14} {:>14} {:>8}   {}\n", "parameter", "prior", "designed std",
                                "multisine std", "ratio", "unit");
  for (std::size_t j = 0; j < d.free.size(); ++j) {
    out += fmt::format("{:<18} {:>12.6g} {:>14.4g} {:>14.4g} {:>8.2f}   {}\n", d.free[j], d.prior[j],
                       d.designed.predicted_std[j], d.naive.predicted_std[j],
                       d.naive.predicted_std[j] / d.designed.predicted_std[j], UnitOf(d.free[j]));
  }
  out += fmt::format("geometric-mean relative std: designed {:.4g}, default multisine {:.4g} ({:.2f}x smaller)\n",
                     d.designed.geometric_mean_relative_std, d.naive.geometric_mean_relative_std,
                     d.naive.geometric_mean_relative_std / d.designed.geometric_mean_relative_std);
  out += fmt::format("predicted for the frf two-mass fit of {} periods of {:.4g} s (the first settles), motor-speed "
                     "noise {:.4g} rad/s and torque noise {:.4g} N m per sample (docs/models.md#joint-excitation-"
                     "design)\n",
                     d.periods, d.period, d.noise, d.torque_noise);
  for (const auto* c : {&d.designed, &d.naive}) {
    out += fmt::format("{}: rms torque {:.4g}, peaks |tau| {:.4g}, |qd_motor| {:.4g} (prior model){}\n", c->name,
                       c->rms, c->peak_torque, c->peak_speed,
                       c->binding.empty() ? std::string("; the same rms") : "; rms set by the " + c->binding + " limit");
  }
  out += fmt::format("within the same limits the default multisine could have rms {:.4g} (crest factor {:.3g} against "
                     "the design's {:.3g}): its stds would then be {:.2f}x those above\n",
                     d.naive_rms_at_limits, d.naive.peak_torque / d.naive.rms, d.designed.peak_torque / d.designed.rms,
                     d.designed.rms / d.naive_rms_at_limits);
  // The strongest lines of the design, by amplitude.
  std::vector<std::size_t> order(d.frequency.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&d](std::size_t a, std::size_t b) { return d.designed.amplitude[a] > d.designed.amplitude[b]; });
  std::string strongest;
  for (std::size_t k = 0; k < std::min<std::size_t>(6, order.size()); ++k) {
    strongest += fmt::format(" {:.4g} Hz ({:.3g})", d.frequency[order[k]], d.designed.amplitude[order[k]]);
  }
  out += fmt::format("strongest lines [amplitude N m]:{}; {} lines from {:.4g} to {:.4g} Hz\n", strongest,
                     d.frequency.size(), d.frequency.front(), d.frequency.back());
  out += d.equivalence < 1.001
             ? fmt::format("D optimum reached after {} iterations (equivalence theorem: max d_l / s = {:.4f})\n",
                           d.iterations, d.equivalence)
             : fmt::format("stopped after {} iterations short of the D optimum (max d_l / s = {:.4f}, 1 there; for "
                           "the a criterion this is only a guide)\n",
                           d.iterations, d.equivalence);
  return out;
}

Json JointDesignJson(const JointDesign& d) {
  Json out = CandidateJson(d, d.designed);
  out["naive"] = CandidateJson(d, d.naive);
  out["noise"] = d.noise;
  out["torque_noise"] = d.torque_noise;
  out["period"] = d.period;
  out["periods"] = d.periods;
  out["iterations"] = d.iterations;
  out["equivalence"] = d.equivalence;
  out["naive"]["rms_torque_at_limits"] = d.naive_rms_at_limits;
  Json prior = Json::object();
  for (std::size_t j = 0; j < d.free.size(); ++j) prior[d.free[j]] = d.prior[j];
  out["prior"] = prior;
  return out;
}

TorqueReference DesignedExcitation(const JointDesign& design, double rate, double duration) {
  TorqueReference r;
  r.torque = SampleJointExcitation(design, design.designed, rate, duration);
  for (std::size_t i = 0; i < r.torque.size(); ++i) r.time.push_back(static_cast<double>(i) / rate);
  return r;
}

std::vector<PlotPanel> JointDesignPanels(const JointDesign& d, double rate) {
  PlotPanel torque{"excitation over one period", "torque [N m]", {}};
  PlotPanel lines{"line amplitudes", "amplitude per line [N m]", {}};
  lines.own_x_label = "frequency [Hz]";
  lines.own_log_x = true;
  for (const auto* c : {&d.designed, &d.naive}) {
    const std::vector<double> samples = SampleJointExcitation(d, *c, rate, d.period);
    std::vector<double> time(samples.size());
    for (std::size_t i = 0; i < time.size(); ++i) time[i] = static_cast<double>(i) / rate;
    torque.lines.push_back({c->name, time, samples});
    PlotLine amplitude{c->name, d.frequency, c->amplitude};
    amplitude.dots = true;
    lines.lines.push_back(std::move(amplitude));
  }
  return {torque, lines};
}

}  // namespace driveid
