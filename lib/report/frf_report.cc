#include "report/frf_report.h"

#include <cmath>
#include <complex>

#include <fmt/format.h>

namespace driveid {
namespace {

constexpr double kGreyCoherence = 0.5;
double Degrees(double radians) { return radians * 180.0 / M_PI; }
double Decibels(const std::complex<double>& h) { return 20.0 * std::log10(std::abs(h)); }

void AppendResponse(std::string& out, const FrequencyResponse& r, std::size_t b,
                    const std::vector<std::complex<double>>* model) {
  const double magnitude = std::abs(r.response[b]);
  out += fmt::format(",{:.9g},{:.6g},{:.6g}", magnitude, Degrees(std::arg(r.response[b])), r.coherence[b]);
  // An unknown std (a response measured elsewhere) leaves its cells empty.
  out += r.log_magnitude_std.empty() ? std::string(",,")
                                     : fmt::format(",{:.6g},{:.6g}", magnitude * r.log_magnitude_std[b],
                                                   Degrees(r.phase_std[b]));
  if (model != nullptr) out += fmt::format(",{:.9g},{:.6g}", std::abs((*model)[b]), Degrees(std::arg((*model)[b])));
}

void AddResponseLines(const FrequencyResponse& r, const std::vector<std::complex<double>>* model,
                      const std::string& name, PlotPanel& magnitude, PlotPanel& phase, PlotPanel& coherence) {
  PlotLine coherent_mag{name + " measured", {}, {}, false, true}, grey_mag{name + " coherence < 0.5", {}, {}, false, false, true};
  PlotLine coherent_phase = coherent_mag, grey_phase = grey_mag;
  for (std::size_t b = 0; b < r.frequency.size(); ++b) {
    const bool coherent = r.coherence[b] >= kGreyCoherence;
    (coherent ? coherent_mag : grey_mag).x.push_back(r.frequency[b]);
    (coherent ? coherent_mag : grey_mag).y.push_back(Decibels(r.response[b]));
    (coherent ? coherent_phase : grey_phase).x.push_back(r.frequency[b]);
    (coherent ? coherent_phase : grey_phase).y.push_back(Degrees(std::arg(r.response[b])));
  }
  for (auto* line : {&grey_mag, &coherent_mag}) {
    if (!line->x.empty()) magnitude.lines.push_back(*line);
  }
  for (auto* line : {&grey_phase, &coherent_phase}) {
    if (!line->x.empty()) phase.lines.push_back(*line);
  }
  if (model != nullptr) {
    PlotLine m{name + " two-mass model", r.frequency, {}, false, false}, p = m;
    for (const auto& h : *model) {
      m.y.push_back(Decibels(h));
      p.y.push_back(Degrees(std::arg(h)));
    }
    magnitude.lines.push_back(m);
    phase.lines.push_back(p);
  }
  coherence.lines.push_back({name + " coherence", r.frequency, r.coherence, false, false});
}

std::string FrequencyText(const FrequencyEstimate& e) {
  return e.value > 0.0 ? fmt::format("{:.5g} +- {:.2g} Hz", e.value, e.standard_error) : std::string("not found");
}

Json FrequencyJson(const FrequencyEstimate& e) {
  if (!(e.value > 0.0)) return nullptr;
  return Json{{"value_hz", e.value}, {"std_hz", e.standard_error}};
}

}  // namespace

std::string FormatFrfCsv(const FrfResult& result) {
  const bool fitted = result.fit.has_value();
  std::string out = fmt::format("# drivetrain-fit frf: {}; rate {} Hz; docs/formats.md#frequency-response-csv\n",
                                result.motor.description, result.rate);
  out += "frequency_hz,magnitude,phase_deg,coherence,magnitude_std,phase_std_deg";
  if (fitted) out += ",model_magnitude,model_phase_deg";
  if (result.link) {
    out += ",link_magnitude,link_phase_deg,link_coherence,link_magnitude_std,link_phase_std_deg";
    if (fitted) out += ",link_model_magnitude,link_model_phase_deg";
  }
  out += "\n";
  for (std::size_t b = 0; b < result.motor.frequency.size(); ++b) {
    out += fmt::format("{:.9g}", result.motor.frequency[b]);
    AppendResponse(out, result.motor, b, fitted ? &result.fit->motor_model : nullptr);
    if (result.link) {
      if (b < result.link->frequency.size() && result.link->frequency[b] == result.motor.frequency[b]) {
        AppendResponse(out, *result.link, b, fitted ? &result.fit->link_model : nullptr);
      } else {
        out += fitted ? ",,,,,,," : ",,,,";
      }
    }
    out += "\n";
  }
  return out;
}

std::vector<PlotPanel> MakeBodePanels(const FrfResult& result) {
  const char* method = result.motor.method == FrequencyMethod::kPeriodic ? "per period" : "Welch";
  PlotPanel magnitude{fmt::format("frequency response ({}, {} averages, {:.3g} Hz bins{})", method,
                                  result.motor.averages, result.motor.resolution,
                                  result.motor.closed_loop ? ", closed loop, with the reference" : ""),
                      "magnitude [dB]", {}};
  PlotPanel phase{"phase", "phase [deg]", {}};
  PlotPanel coherence{"coherence (bins below 0.5 grey above)", "coherence", {}, 0.0, 1.0};
  AddResponseLines(result.motor, result.fit ? &result.fit->motor_model : nullptr, "motor", magnitude, phase, coherence);
  if (result.link) {
    AddResponseLines(*result.link, result.fit ? &result.fit->link_model : nullptr, "link", magnitude, phase, coherence);
  }
  return {magnitude, phase, coherence};
}

std::string FormatFrfSummary(const FrfResult& result) {
  std::string out = fmt::format("frequency response: {} at {:.6g} Hz, bins of {:.4g} Hz\n", result.motor.description,
                                result.rate, result.motor.resolution);
  for (const auto& note : result.notes) out += "note: " + note + "\n";
  out += fmt::format("read from the response (band {:.4g} .. {:.4g} Hz): resonance {}, anti-resonance {}\n",
                     result.read.band_low, result.read.band_high, FrequencyText(result.read.resonance),
                     FrequencyText(result.read.antiresonance));
  if (result.fit) {
    out += fmt::format("two-mass fit (band {:.4g} .. {:.4g} Hz): resonance {}, anti-resonance {}\n",
                       result.fit->band_low, result.fit->band_high, FrequencyText(result.fit->resonance),
                       FrequencyText(result.fit->antiresonance));
  }
  return out;
}

Json FrfJson(const FrfResult& result) {
  Json j;
  j["method"] = result.motor.description;
  j["rate_hz"] = result.rate;
  j["resolution_hz"] = result.motor.resolution;
  j["averages"] = result.motor.averages;
  j["closed_loop"] = result.motor.closed_loop;
  j["read"] = Json{{"resonance", FrequencyJson(result.read.resonance)},
                   {"antiresonance", FrequencyJson(result.read.antiresonance)},
                   {"band_hz", Json::array({result.read.band_low, result.read.band_high})}};
  if (result.fit) {
    j["fitted"] = Json{{"resonance", FrequencyJson(result.fit->resonance)},
                       {"antiresonance", FrequencyJson(result.fit->antiresonance)},
                       {"band_hz", Json::array({result.fit->band_low, result.fit->band_high})}};
  }
  j["notes"] = result.notes;
  j["warnings"] = result.warnings;
  return j;
}

}  // namespace driveid
