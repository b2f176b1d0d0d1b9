#include "sim/axis_experiment.h"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/option_check.h"

#include "sim/noise.h"

namespace driveid {
namespace {

double Quantised(double q, double resolution) { return resolution > 0.0 ? std::floor(q / resolution) * resolution : q; }

// The axis following a reference's samples exactly.
AxisLog SimulateAxisReference(const AxisParameters& params, const AxisExperiment& e) {
  RequireOption(std::isfinite(e.noise) && e.noise >= 0.0, "‹noise›", e.noise, "noise >= 0");
  RequireOption(std::isfinite(e.resolution) && e.resolution >= 0.0, "‹resolution›", e.resolution, "resolution >= 0");
  const AxisReference& r = e.reference;
  RequireSampleCount(static_cast<double>(r.time.size()), kMinAxisLogSamples, "‹reference› " + r.path);
  GaussianNoise noise(e.seed);
  AxisLog log;
  log.path = "simulated";
  for (std::size_t k = 0; k < r.time.size(); ++k) {
    log.time.push_back(r.time[k]);
    log.position.push_back(Quantised(r.position[k], e.resolution));
    log.force.push_back(CalcAxisForce(params, r.position[k], r.rate[k], r.acceleration[k]) +
                        (e.noise > 0.0 ? noise.Next(e.noise) : 0.0));
  }
  return log;
}

}  // namespace

AxisLog SimulateAxisExperiment(const AxisParameters& params, const AxisExperiment& e) {
  if (e.profile == "reference") return SimulateAxisReference(params, e);
  RequireOption(std::isfinite(e.rate) && e.rate > 0.0, "‹rate›", e.rate, "rate > 0 Hz");
  RequireOption(std::isfinite(e.duration) && e.duration > 0.0, "‹duration›", e.duration, "duration > 0 s");
  RequireSampleCount(std::round(e.duration * e.rate) + 1, kMinAxisLogSamples,
                     fmt::format("‹duration› {} at ‹rate› {}", e.duration, e.rate));
  RequireOption(std::isfinite(e.noise) && e.noise >= 0.0, "‹noise›", e.noise, "noise >= 0");
  RequireOption(std::isfinite(e.resolution) && e.resolution >= 0.0, "‹resolution›", e.resolution, "resolution >= 0");
  if (e.profile != "multisine" && e.profile != "constant") {
    throw OptionError("‹profile› " + e.profile + ": choose multisine, constant or (with ‹reference›) reference");
  }
  GaussianNoise noise(e.seed);
  AxisLog log;
  log.path = "simulated";
  const long samples = std::lround(e.duration * e.rate) + 1;
  const double w1 = 2 * M_PI * 0.3, w2 = 2 * M_PI * 1.1, w3 = 2 * M_PI * 2.3;
  for (long k = 0; k < samples; ++k) {
    const double t = static_cast<double>(k) / e.rate;
    double q, rate, acceleration;
    if (e.profile == "constant") {
      q = e.speed * t;
      rate = e.speed;
      acceleration = 0.0;
    } else {
      q = e.amplitude * (0.6 * std::sin(w1 * t) + 0.3 * std::sin(w2 * t + 1) + 0.1 * std::sin(w3 * t + 2));
      rate = e.amplitude * (0.6 * w1 * std::cos(w1 * t) + 0.3 * w2 * std::cos(w2 * t + 1) + 0.1 * w3 * std::cos(w3 * t + 2));
      acceleration = -e.amplitude * (0.6 * w1 * w1 * std::sin(w1 * t) + 0.3 * w2 * w2 * std::sin(w2 * t + 1) +
                                     0.1 * w3 * w3 * std::sin(w3 * t + 2));
    }
    log.time.push_back(t);
    log.position.push_back(Quantised(q, e.resolution));
    log.force.push_back(CalcAxisForce(params, q, rate, acceleration) + (e.noise > 0.0 ? noise.Next(e.noise) : 0.0));
  }
  return log;
}

}  // namespace driveid
