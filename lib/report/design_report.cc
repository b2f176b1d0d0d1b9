#include "report/design_report.h"

#include <cmath>

#include <fmt/format.h>

namespace driveid {
namespace {

std::string UnitOf(const std::string& key, bool linear) {
  const auto* row = FindParameter(AxisParameterTable(), key);
  return row ? AxisUnit(row->spec, linear) : "";
}

Json PeaksJson(const AxisDesignPeaks& p) {
  return {{"position", p.position}, {"speed", p.rate}, {"acceleration", p.acceleration}, {"torque", p.torque}};
}

Json CandidateJson(const AxisDesign& d, const AxisDesignCandidate& c) {
  Json stds = Json::object();
  for (std::size_t j = 0; j < d.free.size(); ++j) stds[d.free[j]] = c.predicted_std[j];
  Json lines = Json::array();
  const auto f = c.reference.LineFrequencies();
  for (std::size_t k = 0; k < f.size(); ++k) {
    lines.push_back({{"frequency", f[k]}, {"cos", c.reference.cosine[k]}, {"sin", c.reference.sine[k]}});
  }
  return {{"predicted_std", stds},
          {"geometric_mean_relative_std", c.geometric_mean_relative_std},
          {"binding_limit", c.binding},
          {"peaks", PeaksJson(c.peaks)},
          {"lines", lines}};
}

}  // namespace

std::string FormatAxisDesign(const AxisDesign& d, bool linear) {
  std::string out = fmt::format("{:<18} {:>12} {:>14} {:>14} {:>8}   {}\n", "parameter", "prior", "designed std",
                                "4 sines std", "ratio", "unit");
  for (std::size_t j = 0; j < d.free.size(); ++j) {
    out += fmt::format("{:<18} {:>12.6g} {:>14.4g} {:>14.4g} {:>8.2f}   {}\n", d.free[j], d.prior[j],
                       d.designed.predicted_std[j], d.naive.predicted_std[j],
                       d.naive.predicted_std[j] / d.designed.predicted_std[j], UnitOf(d.free[j], linear));
  }
  out += fmt::format("geometric-mean relative std: designed {:.4g}, four sines {:.4g} ({:.2f}x smaller)\n",
                     d.designed.geometric_mean_relative_std, d.naive.geometric_mean_relative_std,
                     d.naive.geometric_mean_relative_std / d.designed.geometric_mean_relative_std);
  out += fmt::format("predicted for a torque noise of {:.4g} per logged sample (docs/models.md#excitation-design)\n",
                     d.noise);
  for (const auto* c : {&d.designed, &d.naive}) {
    out += fmt::format("{}: peaks |q| {:.4g}, |qd| {:.4g}, |qdd| {:.4g}, |tau| {:.4g} (prior model); amplitude set by "
                       "the {} limit\n",
                       c->name, c->peaks.position, c->peaks.rate, c->peaks.acceleration, c->peaks.torque, c->binding);
  }
  std::string lines;
  for (double f : d.designed.reference.LineFrequencies()) lines += fmt::format(" {:.4g}", f);
  out += fmt::format("lines [Hz]:{} (period {:.4g} s, band {:.4g} to {:.4g} Hz); {} evaluations\n", lines, d.period,
                     d.band_low, d.band_high, d.evaluations);
  return out;
}

Json AxisDesignJson(const AxisDesign& d) {
  Json out = CandidateJson(d, d.designed);
  out["naive"] = CandidateJson(d, d.naive);
  out["naive"]["name"] = d.naive.name;
  out["noise"] = d.noise;
  out["period"] = d.period;
  out["band"] = {d.band_low, d.band_high};
  Json prior = Json::object();
  for (std::size_t j = 0; j < d.free.size(); ++j) prior[d.free[j]] = d.prior[j];
  out["prior"] = prior;
  return out;
}

AxisReference DesignedReference(const AxisDesign& design, const AxisParameters& prior, double rate, double duration) {
  SampledReference s = SampleReference(design.designed.reference, prior, rate, duration);
  return {"", std::move(s.time), std::move(s.position), std::move(s.rate), std::move(s.acceleration)};
}

std::vector<PlotPanel> AxisDesignPanels(const AxisDesign& d, const AxisParameters& prior, double rate) {
  PlotPanel position{"reference over one period", "position [rad or m]", {}};
  PlotPanel torque{"", "torque of the prior [N m or N]", {}};
  PlotPanel lines{"line amplitudes", "|qdd| per line [/s^2]", {}};
  lines.own_x_label = "frequency [Hz]";
  lines.own_log_x = true;
  for (const auto* c : {&d.designed, &d.naive}) {
    const SampledReference s = SampleReference(c->reference, prior, rate, d.period);
    position.lines.push_back({c->name, s.time, s.position});
    torque.lines.push_back({c->name, s.time, s.torque});
    PlotLine amplitude{c->name, c->reference.LineFrequencies(), {}};
    amplitude.dots = true;
    for (std::size_t k = 0; k < amplitude.x.size(); ++k) {
      const double w = 2.0 * M_PI * amplitude.x[k];
      amplitude.y.push_back(w * w * std::hypot(c->reference.cosine[k], c->reference.sine[k]));
    }
    lines.lines.push_back(std::move(amplitude));
  }
  return {position, torque, lines};
}

}  // namespace driveid
